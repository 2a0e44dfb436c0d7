// Scenes for normal and bump mapping, with the textures they read written beside them (EXR,
// linear): a plane whose every pixel has a closed-form value, and a lit box of mapped surfaces
// with a glass sphere for ERPT.
#pragma once

#include <string>

#include "support/test_support.h"

namespace erpt::test {

// A constant normal map tilting the normal by `tiltDegrees` towards +u (normal.exr, 4x4).
std::string writeTiltNormalMap(const TempDir& dir, float tiltDegrees);
// Heights h = slope * u across the texture (ramp.exr, 64 texels wide, 4 high).
std::string writeRampHeights(const TempDir& dir, float slope);

// The rectangle [-1, 1]^2 (normal +z, uv = (x + 1, y + 1) / 2), diffuse `albedo`, wrapped in
// `wrapper` (a whole <bsdf> element around the diffuse one, "%s" where the diffuse goes),
// under a directional light along -z of irradiance `irradiance`, seen from z = 2 by a camera
// whose view lies inside the plane: every pixel is albedo / pi * irradiance * cos(normal, z).
std::string writeMappedPlaneScene(const TempDir& dir, const std::string& wrapper, float albedo, float irradiance);

// A floor with sinusoidal bumps and a back wall with a tilted normal map, a glass sphere and a
// small area light (64x64, box filter): glossy-looking mapped diffuse vertices next to
// caustics, for ERPT against the path tracer.
std::string writeMappedBoxScene(const TempDir& dir);

}  // namespace erpt::test
