// Renders against an image known exactly (a closed form): per-block z-scores over independent
// runs and the whole image's ratio to the exact value, for the tests whose reference no
// renderer made (tests/integrators/closed_forms_test.cpp).
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "erpt/render.h"

namespace erpt::test {

// The exact box-filtered image of a scene: each pixel the mean of `radiance` over an n x n grid
// of film positions inside it (radiance arriving along the camera ray through the position).
RgbImage exactImage(const Scene& scene, int width, int height, int subdivisions,
                    const std::function<Color(Vec3 origin, Vec3 direction)>& radiance);

struct ClosedFormResult {
  double ratio = 0, ratioError = 0;  // whole image: rendered / exact luminance, its standard error
  double meanSquare = 0, worst = 0;  // per-block z = (mean - exact) / standard error of the mean
  int blocks = 0;
};

// `runs` renders (seeds seed, seed + 1, ...) of `settings` against `exact`, luminance summed
// per block x block pixels. The standard errors come from the spread of the runs (Student's t
// with runs - 1 degrees of freedom, hence the bounds: the tests use 24 runs, where a |z| above
// 5 has probability 5e-5 per block), plus 1e-4 of the exact value for float rounding.
ClosedFormResult compareWithClosedForm(const Scene& scene, const RenderSettings& settings, const RgbImage& exact,
                                       int runs, uint64_t seed, int block);

}  // namespace erpt::test
