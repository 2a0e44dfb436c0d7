// Fuzz target: the Mitsuba XML scene loader (every plugin's parameters, includes, defaults,
// references), on one scene file with no files beside it.
#include "erpt/scene_loader.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = erpt::fuzz::writeInput("scene.xml", data, size);
  erpt::fuzz::expectCleanFailure([&] { erpt::loadScene(path); }, erpt::fuzz::Place::Line);
  return 0;
}
