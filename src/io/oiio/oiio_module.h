// The interface of the OpenImageIO plugin module (built as liberpt_oiio.so, opened with
// dlopen by image_module.cpp). One exported C symbol returns the function table; the
// functions themselves use C++ types (the module is built with the same compiler and flags).
#pragma once

#include <string>

#include "erpt/image_io.h"

namespace erpt {

struct OiioModuleApi {
  int version;  // kOiioModuleVersion: guards against a stale module beside a newer binary
  bool (*read)(const char* path, RgbImage& image, bool& isSrgb, std::string& error);
  bool (*write)(const char* path, int width, int height, bool isFloat, const void* pixels, std::string& error);
};
constexpr int kOiioModuleVersion = 1;

}  // namespace erpt

extern "C" const erpt::OiioModuleApi* erptOiioModule();
