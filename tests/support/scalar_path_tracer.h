// An independent, deliberately plain path tracer for cross-checking the wavefront one: one
// ray at a time through rtcIntersect1, no queues, no next-event estimation and no MIS (pure
// BSDF sampling, emission counted where a path hits it), its own RNG. It shares only the
// BSDFs and the scene with the renderer.
#pragma once

#include "erpt/image_io.h"
#include "erpt/scene.h"

namespace erpt::test {

// Box-filtered image of `spp` samples per pixel; also returns each pixel's sample variance
// of the mean (for statistical comparisons).
RgbImage scalarPathTrace(const Scene& scene, int width, int height, int spp, int maxDepth, uint64_t seed,
                         RgbImage* varianceOfMean = nullptr);

}  // namespace erpt::test
