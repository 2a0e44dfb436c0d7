// Internal to the scene loader: errors in the files a scene names (meshes, images, included
// scenes) that have no line of their own to point at. Text keeps its lines: OBJ statements,
// ASCII PLY values, PLY headers and included XML are reported where they are. Binary data
// (a binary PLY's body, .serialized meshes, images) and files that cannot be opened or read
// have none; their readers report them at line 0 (with a byte offset where it helps), and the
// loader reports them at the XML line that names the file, the file's name leading the cause:
//   scene.xml:12: error: /scenes/m.serialized: vertex index 9 of triangle 3 out of range (3 vertices)
// so that every rejection is one "file:line: error: cause" line a user can jump to.
#pragma once

#include "erpt/error.h"

namespace erpt::xml {

// Runs `read` (which reads the file named at `reference`) and returns what it returns.
template <class Read>
auto readReferencedFile(const SourceLocation& reference, Read read) -> decltype(read()) {
  try {
    return read();
  } catch (const InputError& e) {
    if (e.where().line > 0) throw;
    throw InputError(reference, e.where().file + ": " + e.cause());
  }
}

}  // namespace erpt::xml
