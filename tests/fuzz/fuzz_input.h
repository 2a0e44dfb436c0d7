// Shared by the fuzz targets: the readers take file paths, so each input is written to a file
// in a directory of this process's own (several targets may run at once), and the errors a
// reader is allowed to raise on bad input are told apart from the ones it must never raise.
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "erpt/error.h"

namespace erpt::fuzz {

// This process's scratch directory (created on first use).
inline const std::filesystem::path& scratchDir() {
  static const std::filesystem::path dir = [] {
    std::filesystem::path d = std::filesystem::temp_directory_path() / ("erpt-fuzz-" + std::to_string(getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

// Writes `size` bytes to `name` in the scratch directory; returns its path. (After a crash
// the input that caused it is still there.)
inline std::string writeInput(const std::string& name, const uint8_t* data, size_t size) {
  const std::filesystem::path path = scratchDir() / name;
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(data), std::streamsize(size));
  return path.string();
}

// Runs `read` on one input: a clear InputError is the expected answer to bad input; any other
// exception escapes (libFuzzer and the driver report it as a crash), as do sanitizer findings.
template <class Read>
void expectCleanFailure(Read read) {
  try {
    read();
  } catch (const InputError&) {
  }
}

}  // namespace erpt::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);
