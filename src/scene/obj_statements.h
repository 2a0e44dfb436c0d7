// Internal to the OBJ reader: the statements behind tinyobjloader's results and errors.
// tinyobjloader keeps no line numbers with what it parsed (an index out of range only shows in
// the triangulated output), and names a statement it cannot parse inside its own error text;
// these find the statement again in the file, so that the error points at its line.
#pragma once

#include <optional>
#include <string>

#include "erpt/error.h"

namespace erpt::obj {

// The line of the statement defining vertex `index` (0-based); 0 if there is none.
int lineOfVertex(const std::string& path, size_t index);

// The first face statement, in file order, that refers to a vertex, normal or texture
// coordinate the file does not define; none when every reference resolves.
std::optional<InputError> badFaceReference(const std::string& path);

// tinyobjloader's parse failure ("Failed parse `f' line(e.g. zero value for face index.
// line 12.)") restated at the statement's line, naming the index it could not take.
InputError parseFailure(const std::string& path, const std::string& tinyobjError);

}  // namespace erpt::obj
