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
// How a block test runs, beyond its scene, settings, runs and seed.
struct BlockTestOptions {
  // false: only measure (print the statistics), assert nothing about them.
  bool assertBounds = true;
  // Samples per pixel of each of the reference's 16 path-traced renders. Scenes whose
  // reference is noisy (a small light's caustic) take more, so that the reference's share of
  // the z denominators stays small; the reference is stored, so this costs no test time.
  int referenceSpp = 128;
  // Called before each of the `runs` renders, and after each with its statistics.
  std::function<void()> beforeEachRun;
  std::function<void(const RenderStats&)> afterEachRun;
};
// `runs` renders with `settings` (64x64, box filter, seeds seed, seed + 1, ...) against 16
// path-traced ones (128 spp unless the options say otherwise), per 8x8 block; expects mean
// z^2 < 2.0 and worst |z| < 4.5. Welch's z with variances from the runs has slightly heavier
// tails than a normal one (mean z^2 about 1.15 when unbiased); 2.0 is about four standard
// errors of that mean away.
// The path-traced side is stored per test in tests/data/block-references (its block means and
// variances, with a key naming the scene's fingerprint, the camera and the settings): with
// ERPT_WRITE_BLOCK_REFERENCES set in the environment the test renders it and writes the file;
// otherwise a missing file, or one whose key differs (the scene or settings changed), fails.
BlockBiasResult expectMatchesPathTracerBlockByBlock(const Scene& scene, RenderSettings settings, int runs, uint64_t seed,
                                                    const BlockTestOptions& options = {});

}  // namespace erpt::test
