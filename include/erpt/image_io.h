// Image files (EXR and PNG directly, every other format through OpenImageIO). Writes are atomic: the image goes to a temporary file
// beside the target and is renamed over it only when complete, so a failed or interrupted
// run never leaves a partial image behind.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "erpt/math.h"

namespace erpt {

struct RgbImage {
  int width = 0, height = 0;
  std::vector<Color> pixels;  // row-major, row 0 at the top
  // Text attributes (name, value): written to and read from EXR headers (a partial render's
  // "erpt:partial"), not to PNG.
  std::vector<std::pair<std::string, std::string>> metadata;
  const std::string* attribute(const std::string& name) const {
    for (const auto& [n, v] : metadata)
      if (n == name) return &v;
    return nullptr;
  }
  Color& at(int x, int y) { return pixels[size_t(y) * width + x]; }
  const Color& at(int x, int y) const { return pixels[size_t(y) * width + x]; }
};

// Reads EXR, PNG and any other format OpenImageIO knows. `isSrgbEncoded` tells whether the file stores
// display-encoded (sRGB) values, as 8-bit PNG/JPEG do. Throws InputError naming the file.
RgbImage readImage(const std::string& path, bool* isSrgbEncoded = nullptr);

// Linear float EXR, or any format OpenImageIO writes by extension (.png gets the tone-mapped
// treatment of writePngAtomic). Throws std::runtime_error on failure, leaving no file behind.
void writeImageAtomic(const std::string& path, const RgbImage& image);
// Threads that may compress one EXR file (OpenEXR's own pool; 1, the default: the calling
// thread alone). The bytes written do not depend on it.
void setExrWriteThreads(int threads);
// Tone-mapped display image: clamp to [0,1], sRGB transfer curve, 8 bits.
void writePngAtomic(const std::string& path, const RgbImage& image);
// The 8-bit sRGB pixels writePngAtomic writes (clamped to [0, 1], non-finite values black), RGB
// row-major from the top.
std::vector<uint8_t> toneMapped8(const RgbImage& image);

// 8-bit RGB pixels as they are (charts, heat maps), rows top to bottom.
void writeRgb8Atomic(const std::string& path, int width, int height, const uint8_t* rgb);

// Any file (checkpoints), written as atomically as the images.
void writeBytesAtomic(const std::string& path, const std::vector<uint8_t>& bytes);

// Remove any temporary image being written (for signal handlers: async-signal-safe).
void removePendingImageFiles();

}  // namespace erpt
