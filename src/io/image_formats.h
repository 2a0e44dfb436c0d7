// The image file readers and writers behind image_io.cpp. EXR and PNG, the formats every
// render writes and most references and textures use, go through OpenEXR and libpng (small
// libraries, loaded in milliseconds). Every other format goes through OpenImageIO, which is
// loaded on first use from a plugin module (oiio/oiio_module.cpp): linking it would make every
// process load its ~250 dependent libraries at start-up (~0.2 s, most of a short render).
#pragma once

#include <cstdint>
#include <string>

#include "erpt/image_io.h"

namespace erpt::image_formats {

// Readers return false with `error` set; values are as stored (PNG: 8-bit values / 255 with
// isSrgb = true, 16-bit values linearised by libpng with isSrgb = false).
bool readExr(const std::string& path, RgbImage& image, std::string& error);
bool readPng(const std::string& path, RgbImage& image, bool& isSrgb, std::string& error);
bool writeExr(const std::string& path, const RgbImage& image, std::string& error);
void setExrThreads(int threads);
bool writePng8(const std::string& path, int width, int height, const uint8_t* rgb, std::string& error);

// Through the OpenImageIO module (loaded here on first call; error names it if it cannot be).
bool readWithOiio(const std::string& path, RgbImage& image, bool& isSrgb, std::string& error);
bool writeWithOiio(const std::string& path, int width, int height, bool isFloat, const void* pixels, std::string& error);

}  // namespace erpt::image_formats
