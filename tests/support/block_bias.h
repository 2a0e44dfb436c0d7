// An integrator against the path tracer block by block (z-scores over independent renders).
#pragma once

#include <cstdint>
#include <functional>

#include "erpt/render.h"

namespace erpt::test {

// render() with its stats copied to `out` (when given), expecting no invalid samples.
RgbImage renderImage(const Scene& scene, const RenderSettings& settings, RenderStats* out = nullptr);

struct BlockBiasResult {
  double meanSquare = 0, worst = 0;
};
// `runs` renders with `settings` (64x64, box filter, seeds seed, seed + 1, ...) against 16
// path-traced ones of 128 spp, per 8x8 block; expects mean z^2 < 2.0 and worst |z| < 4.5
// unless `assertBounds` is false (then it only measures). Welch's z with variances from the
// runs has slightly heavier tails than a normal one (mean z^2 about 1.15 when unbiased); 2.0 is
// about four standard errors of that mean away.
// The path-traced side is stored per test in tests/data/block-references (its block means and
// variances, with a key naming the scene's fingerprint, the camera and the settings): with
// ERPT_WRITE_BLOCK_REFERENCES set in the environment the test renders it and writes the file;
// otherwise a missing file, or one whose key differs (the scene or settings changed), fails.
// `beforeEachRun` (when set) is called before each of the `runs` renders, `afterEachRun` with
// each one's statistics.
BlockBiasResult expectMatchesPathTracerBlockByBlock(const Scene& scene, RenderSettings settings, int runs, uint64_t seed,
                                                    bool assertBounds = true,
                                                    const std::function<void()>& beforeEachRun = {},
                                                    const std::function<void(const RenderStats&)>& afterEachRun = {});

}  // namespace erpt::test
