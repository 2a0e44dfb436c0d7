// Image files: EXR and PNG through OpenEXR and libpng, other formats through the OpenImageIO
// plugin module, and that renders of EXR/PNG never load OpenImageIO (process start-up).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "erpt/error.h"
#include "erpt/image_io.h"
#include "support/test_support.h"

namespace erpt {
namespace {

// A small non-square image with values an 8-bit or RGBE file cannot hold exactly.
RgbImage testImage() {
  RgbImage img;
  img.width = 7;
  img.height = 3;
  for (int i = 0; i < img.width * img.height; ++i)
    img.pixels.push_back(Color(0.013f * float(i), std::pow(1.7f, float(i)) * 1e-3f, i % 2 ? -2.5f : 1e6f));
  return img;
}

float srgbEncode(float v) {
  v = std::min(1.0f, std::max(0.0f, v));
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

TEST(ImageIo, ExrRoundTripIsExactAndNotDisplayEncoded) {
  test::TempDir dir;
  const RgbImage img = testImage();
  writeImageAtomic(dir.file("a.exr"), img);
  bool srgb = true;
  const RgbImage back = readImage(dir.file("a.exr"), &srgb);
  EXPECT_FALSE(srgb);
  ASSERT_EQ(back.width, img.width);
  ASSERT_EQ(back.height, img.height);
  for (size_t i = 0; i < img.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(back.pixels[i][c], img.pixels[i][c]) << "pixel " << i << " channel " << c;
  // Upper-case extension: same format.
  writeImageAtomic(dir.file("B.EXR"), img);
  EXPECT_EQ(readImage(dir.file("B.EXR")).pixels[5].y, img.pixels[5].y);
}

TEST(ImageIo, PngHoldsTheSrgbEncodedValues) {
  test::TempDir dir;
  const RgbImage img = testImage();
  writePngAtomic(dir.file("a.png"), img);
  bool srgb = false;
  const RgbImage back = readImage(dir.file("a.png"), &srgb);
  EXPECT_TRUE(srgb);
  ASSERT_EQ(back.width, img.width);
  ASSERT_EQ(back.height, img.height);
  for (size_t i = 0; i < img.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(back.pixels[i][c], srgbEncode(img.pixels[i][c]), 0.5f / 255.0f + 1e-6f);
}

TEST(ImageIo, OtherFormatsGoThroughOpenImageIo) {
  test::TempDir dir;
  // RGBE: one shared exponent, 8-bit mantissas: each channel within 1% of the pixel's largest.
  RgbImage img;
  img.width = 5;
  img.height = 2;
  for (int i = 0; i < 10; ++i) img.pixels.push_back(Color(0.2f + 0.01f * float(i), 0.5f, 1.0f + float(i * i)));
  writeImageAtomic(dir.file("a.hdr"), img);
  bool srgb = true;
  const RgbImage back = readImage(dir.file("a.hdr"), &srgb);
  EXPECT_FALSE(srgb);
  ASSERT_EQ(back.width, img.width);
  ASSERT_EQ(back.height, img.height);
  for (size_t i = 0; i < img.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(back.pixels[i][c], img.pixels[i][c], 0.01f * maxComponent(img.pixels[i]));
  const uint8_t rgb[6] = {0, 64, 128, 255, 1, 2};
  writeRgb8Atomic(dir.file("b.tga"), 2, 1, rgb);
  const RgbImage tga = readImage(dir.file("b.tga"), &srgb);
  EXPECT_TRUE(srgb);
  ASSERT_EQ(tga.width, 2);
  EXPECT_NEAR(tga.pixels[1].x, 1.0f, 1e-6f);
  EXPECT_NEAR(tga.pixels[0].z, 128.0f / 255.0f, 1e-6f);
}

TEST(ImageIo, UnreadableFilesNameTheFile) {
  test::TempDir dir;
  for (const char* name : {"missing.exr", "missing.png", "missing.jpg", "garbage.exr", "garbage.png"}) {
    const std::string path = dir.file(name);
    if (std::string(name).rfind("garbage", 0) == 0) dir.write(name, "not an image at all");
    try {
      readImage(path);
      ADD_FAILURE() << name << " was read";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
      const bool missing = std::string(name).rfind("missing", 0) == 0;
      EXPECT_NE(std::string(e.what()).find(missing ? "cannot open image" : "cannot read image"), std::string::npos) << e.what();
    }
  }
  // A failed write leaves nothing behind.
  EXPECT_THROW(writeImageAtomic(dir.file("no-such-dir/a.exr"), testImage()), std::runtime_error);
  EXPECT_THROW(writeImageAtomic(dir.file("a.unknown-format"), testImage()), std::runtime_error);
  for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
    EXPECT_EQ(entry.path().filename().string().rfind("garbage", 0), 0u) << entry.path();
}

// The start-up cost the plugin module removes: a render writing EXR + PNG and a diff of EXR
// files load no OpenImageIO library (LD_DEBUG=files lists every object the loader opens).
TEST(ImageIo, RendersOfExrAndPngNeverLoadOpenImageIo) {
  test::TempDir dir;
  const std::string out = dir.file("r.exr");
  test::CommandResult render = test::runCliWithEnvironment(
      "LD_DEBUG=files", "render -q " + test::sourceDir() + "/scenes/default/scene.xml --width 16 --height 16 --spp 1 -o " + out);
  ASSERT_EQ(render.exitCode, 0) << render.output;
  EXPECT_NE(render.output.find("libembree3"), std::string::npos) << "LD_DEBUG gave no library list";
  EXPECT_EQ(render.output.find("libOpenImageIO"), std::string::npos);
  test::CommandResult diff = test::runCliWithEnvironment("LD_DEBUG=files", "diff " + out + " " + out);
  ASSERT_EQ(diff.exitCode, 0) << diff.output;
  EXPECT_EQ(diff.output.find("libOpenImageIO"), std::string::npos);
  // ... while a format only OpenImageIO reads does load it.
  writeImageAtomic(dir.file("r.hdr"), readImage(out));
  test::CommandResult hdr = test::runCliWithEnvironment("LD_DEBUG=files", "diff " + dir.file("r.hdr") + " " + out);
  ASSERT_EQ(hdr.exitCode, 0) << hdr.output;
  EXPECT_NE(hdr.output.find("libOpenImageIO"), std::string::npos);
}

}  // namespace
}  // namespace erpt
