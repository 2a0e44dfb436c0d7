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
// The sphere under Mitsuba 0.6's `sky` (turbidity 2.5, the sun 33 degrees up, behind the
// sphere as seen from the camera, so that its caustic falls towards it), on a floor that
// reaches to the top of the image (the sky is black below the horizon).
std::string writeSkyGlassScene(const TempDir& dir);
// The same under `sunsky`: the sky plus the sun drawn 25 times as wide (6.7 degrees; the same
// power), scaled to 1/5 so that its irradiance is about twice the sky's. Its caustic is a bright patch on
// the floor, found by the path tracer only through BSDF samples that hit the disk.
std::string writeSunskyGlassScene(const TempDir& dir);

}  // namespace erpt::test
