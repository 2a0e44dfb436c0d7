// A scene lit only by an environment map the test writes itself: a sky (blue, darker towards
// the horizon), a dim brown ground half and a small very bright "sun" patch of 3x3 pixels,
// over a diffuse floor with a glass sphere (the sun casts a caustic through it).
#pragma once

#include <string>

#include "erpt/image_io.h"
#include "support/test_support.h"

namespace erpt::test {

// The 64x32 lat-long sky image described above (linear radiance).
RgbImage skyImage(bool withSun = true);
// Writes sky.exr and scene.xml (64x64 film, box filter) into `dir`; returns the scene's path.
std::string writeEnvmapGlassScene(const TempDir& dir);

}  // namespace erpt::test
