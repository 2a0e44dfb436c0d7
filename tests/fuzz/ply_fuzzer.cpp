// Fuzz target: the PLY reader (ascii and both binary byte orders).
#include "scene/mesh_io.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = erpt::fuzz::writeInput("mesh.ply", data, size);
  erpt::Warnings warnings;
  erpt::fuzz::expectCleanFailure([&] { erpt::readPly(path, warnings); }, erpt::fuzz::Place::LineOrByte);
  return 0;
}
