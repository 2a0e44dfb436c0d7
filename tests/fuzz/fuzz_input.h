// Shared by the fuzz targets: the readers take file paths, so each input is written to a file
// in a directory of this process's own (several targets may run at once), and the errors a
// reader is allowed to raise on bad input are told apart from the ones it must never raise;
// the allowed one must also read as one "file:line: error: cause" line.
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

// Where an error about the input must point (src/scene/referenced_file.h has the rule).
enum class Place {
  Line,        // a line: text formats, and the scene loader for everything
  LineOrByte,  // a line, or for binary data a byte offset ("... at byte N", line 0)
  File,        // the file as a whole will do: .serialized has no lines
};

// Aborts (a crash to libFuzzer and the driver) unless `e` is one line that begins with its
// place and "error: ", and names a line where `place` asks for one.
inline void checkMessage(const InputError& e, Place place) {
  const std::string message = e.what(), start = e.where().str() + ": error: ";
  const bool hasLine = e.where().line > 0;
  const bool placed = place == Place::File || hasLine ||
                      (place == Place::LineOrByte && e.cause().find(" at byte ") != std::string::npos);
  if (message.find_first_of("\r\n") == std::string::npos && message.compare(0, start.size(), start) == 0 &&
      !e.cause().empty() && placed)
    return;
  std::fprintf(stderr, "badly placed or formed error message: %s\n", message.c_str());
  std::abort();
}

// Runs `read` on one input: a clear InputError is the expected answer to bad input; any other
// exception escapes (libFuzzer and the driver report it as a crash), as do sanitizer findings.
template <class Read>
void expectCleanFailure(Read read, Place place) {
  try {
    read();
  } catch (const InputError& e) {
    checkMessage(e, place);
  }
}

}  // namespace erpt::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);
