// Reading whole input files, with the InputError every reader reports on failure.
#pragma once

#include <string>

namespace erpt {

// Throws InputError("<path>: error: cannot open <what>", or "is a directory, not a <what>")
// unless the file can be opened for reading; for readers that open it themselves.
void requireReadableFile(const std::string& path, const std::string& what);

// The file's bytes; throws InputError as requireReadableFile does, or "cannot read <what>".
std::string readWholeFile(const std::string& path, const std::string& what);

}  // namespace erpt
