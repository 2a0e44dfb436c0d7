// Stage kernels: each processes one index range of its queues (forEachRange calls them
// across threads). A stage reads and writes only the queues it is given.
#pragma once

#include "erpt/camera.h"
#include "erpt/light_sampler.h"
#include "erpt/pixel_filter.h"
#include "erpt/queues.h"

namespace erpt {

// What stages read but never write.
struct StageContext {
  const Scene& scene;
  const Camera& camera;
  const PixelFilter& filter;
  const LightSampler& lights;
  uint64_t seed;
  int width;
  int spp;
  int maxDepth;
};

// Random-number dimensions of one camera sample (stream key = (pixel, sample)).
enum SampleDim : uint32_t {
  kDimFilmX = 0, kDimFilmY, kDimLightPick, kDimLight1, kDimLight2, kDimLobe, kDimBsdf1, kDimBsdf2
};

uint64_t sampleKey(uint64_t seed, uint32_t pixel, uint32_t sample);

// Camera rays for samples[range]: film positions stratified per pixel (Latin hypercube
// over the pixel's samples) and importance-sampled from the pixel filter.
void stageGenerateCameraRays(const StageContext& ctx, const DirectSampleQueue& samples, RayQueue& rays,
                             IndexRange range);

// Direct lighting at the first hit: adds emission seen directly, fills `shadowRays` with
// next-event rays (contribution kept in samples.shadow*) and `bsdfRays` with BSDF-sampled
// rays (weight and pdf kept in samples.bsdf*). Unused rays are disabled.
void stageShadeDirect(const StageContext& ctx, const RayQueue& cameraRays, const HitQueue& hits,
                      DirectSampleQueue& samples, RayQueue& shadowRays, RayQueue& bsdfRays, IndexRange range);

// After tracing: adds unoccluded next-event contributions and MIS-weighted emission found by
// the BSDF rays.
void stageGatherDirect(const StageContext& ctx, const RayQueue& shadowRays, const RayQueue& bsdfRays,
                       const HitQueue& bsdfHits, DirectSampleQueue& samples, IndexRange range);

inline float powerHeuristic(float a, float b) {
  a *= a;
  b *= b;
  return a + b > 0 ? a / (a + b) : 0.0f;
}

}  // namespace erpt
