#include "erpt/file_util.h"

#include <fstream>
#include <iterator>

#include "erpt/error.h"

namespace erpt {

std::string readWholeFile(const std::string& path, const std::string& what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError({path, 0}, "cannot open " + what);
  std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError({path, 0}, "cannot read " + what);
  return data;
}

}  // namespace erpt
