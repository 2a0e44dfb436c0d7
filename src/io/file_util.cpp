#include "io/file_util.h"

#include <filesystem>
#include <fstream>
#include <ios>
#include <iterator>

#include "erpt/error.h"

namespace erpt {

void requireReadableFile(const std::string& path, const std::string& what) {
  // Opening a directory succeeds, and reading from it throws std::ios_base::failure (libstdc++).
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError({path, 0}, "is a directory, not a " + what);
  if (!std::ifstream(path, std::ios::binary)) throw InputError({path, 0}, "cannot open " + what);
}

std::string readWholeFile(const std::string& path, const std::string& what) {
  requireReadableFile(path, what);
  std::ifstream in(path, std::ios::binary);
  try {
    std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in.bad()) return data;
  } catch (const std::ios_base::failure&) {
  }
  throw InputError({path, 0}, "cannot read " + what);
}

}  // namespace erpt
