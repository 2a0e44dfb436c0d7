// OpenImageIO behind the plugin interface of oiio_module.h: every image format it knows.
#include "oiio_module.h"

#include <OpenImageIO/imageio.h>

namespace erpt {

namespace {

bool readImageFile(const char* path, RgbImage& image, bool& isSrgb, std::string& error) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) {
    error = OIIO::geterror();
    return false;
  }
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) {
    error = "image has no pixels";
    return false;
  }
  std::vector<float> data(size_t(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, data.data())) {
    error = in->geterror();
    return false;
  }
  image.width = spec.width;
  image.height = spec.height;
  image.pixels.resize(size_t(spec.width) * spec.height);
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    const float* px = &data[i * spec.nchannels];
    image.pixels[i] = spec.nchannels >= 3 ? Color(px[0], px[1], px[2]) : Color(px[0]);
  }
  const std::string space = spec.get_string_attribute("oiio:ColorSpace");
  isSrgb = space == "sRGB" ||
           (space.empty() && (spec.format == OIIO::TypeDesc::UINT8 || spec.format == OIIO::TypeDesc::UINT16));
  return true;
}

bool writeImageFile(const char* path, int width, int height, bool isFloat, const void* pixels, std::string& error) {
  const OIIO::TypeDesc type = isFloat ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8;
  auto out = OIIO::ImageOutput::create(path);
  if (!out) {
    error = "unsupported image format (" + OIIO::geterror() + ")";
    return false;
  }
  OIIO::ImageSpec spec(width, height, 3, type);
  if (!out->open(path, spec) || !out->write_image(type, pixels) || !out->close()) {
    error = out->geterror();
    return false;
  }
  return true;
}

const OiioModuleApi kApi{kOiioModuleVersion, readImageFile, writeImageFile};

}  // namespace

}  // namespace erpt

extern "C" const erpt::OiioModuleApi* erptOiioModule() { return &erpt::kApi; }
