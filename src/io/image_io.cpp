#include "erpt/image_io.h"

#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include <OpenImageIO/imageio.h>

#include "erpt/error.h"

namespace erpt {

namespace {

// The temporary file being written, for removePendingImageFiles() (a plain buffer, so a
// signal handler may read it).
char pendingPath[4096] = {0};

std::string temporaryPathFor(const std::string& path) {
  namespace fs = std::filesystem;
  fs::path p(path);
  fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  // Keep the extension last: OpenImageIO picks the format from it.
  return (dir / ("." + p.stem().string() + ".partial-" + std::to_string(getpid()) + p.extension().string())).string();
}

void writeAtomic(const std::string& path, int width, int height, OIIO::TypeDesc type, const void* data) {
  std::string tmp = temporaryPathFor(path);
  std::snprintf(pendingPath, sizeof(pendingPath), "%s", tmp.c_str());
  auto fail = [&](const std::string& why) {
    std::remove(tmp.c_str());
    pendingPath[0] = 0;
    throw std::runtime_error("cannot write '" + path + "': " + why);
  };
  auto out = OIIO::ImageOutput::create(tmp);
  if (!out) fail("unsupported image format (" + OIIO::geterror() + ")");
  OIIO::ImageSpec spec(width, height, 3, type);
  if (!out->open(tmp, spec)) fail(out->geterror());
  if (!out->write_image(type, data)) fail(out->geterror());
  if (!out->close()) fail(out->geterror());
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) fail(ec.message());
  pendingPath[0] = 0;
}

}  // namespace

void removePendingImageFiles() {
  if (pendingPath[0]) unlink(pendingPath);
}

RgbImage readImage(const std::string& path, bool* isSrgbEncoded) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw InputError({path, 0}, "cannot read image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
    throw InputError({path, 0}, "image has no pixels");
  std::vector<float> data(size_t(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, data.data()))
    throw InputError({path, 0}, "cannot read image: " + in->geterror());
  RgbImage img;
  img.width = spec.width;
  img.height = spec.height;
  img.pixels.resize(size_t(spec.width) * spec.height);
  for (size_t i = 0; i < img.pixels.size(); ++i) {
    const float* px = &data[i * spec.nchannels];
    img.pixels[i] = spec.nchannels >= 3 ? Color(px[0], px[1], px[2]) : Color(px[0]);
  }
  if (isSrgbEncoded) {
    std::string space = spec.get_string_attribute("oiio:ColorSpace");
    *isSrgbEncoded = space == "sRGB" || (space.empty() && (spec.format == OIIO::TypeDesc::UINT8 ||
                                                           spec.format == OIIO::TypeDesc::UINT16));
  }
  return img;
}

void writeImageAtomic(const std::string& path, const RgbImage& image) {
  writeAtomic(path, image.width, image.height, OIIO::TypeDesc::FLOAT, image.pixels.data());
}

void writeRgb8Atomic(const std::string& path, int width, int height, const uint8_t* rgb) {
  writeAtomic(path, width, height, OIIO::TypeDesc::UINT8, rgb);
}

void writePngAtomic(const std::string& path, const RgbImage& image) {
  std::vector<uint8_t> bytes(image.pixels.size() * 3);
  for (size_t i = 0; i < image.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      float v = image.pixels[i][c];
      v = std::isfinite(v) ? std::min(1.0f, std::max(0.0f, v)) : 0.0f;
      v = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
      bytes[i * 3 + c] = uint8_t(std::lround(v * 255.0f));
    }
  writeAtomic(path, image.width, image.height, OIIO::TypeDesc::UINT8, bytes.data());
}

}  // namespace erpt
