// Reading whole input files, with the InputError every reader reports on failure.
#pragma once

#include <string>

namespace erpt {

// The file's bytes; throws InputError("<path>: error: cannot open <what>") when unreadable.
std::string readWholeFile(const std::string& path, const std::string& what);

}  // namespace erpt
