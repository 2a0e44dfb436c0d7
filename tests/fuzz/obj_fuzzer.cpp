// Fuzz target: the Wavefront OBJ reader.
#include "scene/mesh_io.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = erpt::fuzz::writeInput("mesh.obj", data, size);
  erpt::Warnings warnings;
  erpt::fuzz::expectCleanFailure([&] { erpt::readObj(path, true, warnings); }, erpt::fuzz::Place::Line);
  return 0;
}
