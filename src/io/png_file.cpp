// 8-bit PNG files through libpng's simplified API (it converts palette, grey and alpha
// images to RGB). 16-bit PNGs are left to OpenImageIO, which keeps their full precision.
#include <png.h>

#include <cstring>
#include <vector>

#include "image_formats.h"

namespace erpt::image_formats {

bool readPng(const std::string& path, RgbImage& image, bool& isSrgb, std::string& error) {
  png_image png;
  std::memset(&png, 0, sizeof(png));
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, path.c_str())) {
    error = png.message;
    return false;
  }
  if (png.format & PNG_FORMAT_FLAG_LINEAR) {  // 16 bits per channel
    png_image_free(&png);
    return readWithOiio(path, image, isSrgb, error);
  }
  png.format = PNG_FORMAT_RGB;
  std::vector<uint8_t> bytes(PNG_IMAGE_SIZE(png));
  if (!png_image_finish_read(&png, nullptr, bytes.data(), 0, nullptr)) {
    error = png.message;
    png_image_free(&png);
    return false;
  }
  image.width = int(png.width);
  image.height = int(png.height);
  image.pixels.resize(size_t(png.width) * png.height);
  for (size_t i = 0; i < image.pixels.size(); ++i)
    image.pixels[i] = Color(bytes[3 * i], bytes[3 * i + 1], bytes[3 * i + 2]) / 255.0f;
  isSrgb = true;
  return true;
}

bool writePng8(const std::string& path, int width, int height, const uint8_t* rgb, std::string& error) {
  png_image png;
  std::memset(&png, 0, sizeof(png));
  png.version = PNG_IMAGE_VERSION;
  png.width = png_uint_32(width);
  png.height = png_uint_32(height);
  png.format = PNG_FORMAT_RGB;
  // Speed over size: at 1024x1024 the default compression took 0.33 s, longer than the EXR
  // beside it, on the critical path at the end of every render.
  png.flags = PNG_IMAGE_FLAG_FAST;
  if (!png_image_write_to_file(&png, path.c_str(), 0, rgb, 0, nullptr)) {
    error = png.message;
    return false;
  }
  return true;
}

}  // namespace erpt::image_formats
