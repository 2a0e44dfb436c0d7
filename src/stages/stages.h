// Stage kernels: each processes one index range of its queues (forEachRange calls them
// across threads). A stage reads and writes only the queues it is given.
#pragma once

#include "models/camera.h"
#include "kernels/kernels.h"
#include "models/light_sampler.h"
#include "models/pixel_filter.h"
#include "core/queues.h"
#include "tracer/ray_queues.h"
#include "core/seeds.h"
#include "kernels/primary_samples.h"
#include "kernels/sample_dimensions.h"
#include "core/rng.h"

namespace erpt {

// What stages read but never write.
struct StageContext {
  const Scene& scene;
  const Camera& camera;
  const PixelFilter& filter;
  const LightSampler& lights;
  uint64_t seed;
  int width;
  int height;
  int spp;
  int maxDepth;
  int rrDepth = 5;  // Russian roulette from this path depth on (Mitsuba's default)
  // stageShadePath shades plain diffuse hits in vector lanes (shade_path_diffuse.h); false:
  // every hit through the scalar body, so that tests and bm_path can compare the two.
  bool vectorShading = true;
  // Replaying chains' primary samples (pssmlt): the path stages draw every number from it,
  // and a path's stream key is its chain's index. nullptr: the counter-based streams.
  PrimarySamples* replay = nullptr;
  // Contributions of paths with fewer segments are left out (pssmlt with a direct pass, which
  // renders those): emission found after `depth` segments counts from depth >= minSegments,
  // a next-event connection from there from depth + 1 >= minSegments.
  int minSegments = 1;
};

// Dimension `dim` of stream `key`: a counter-based random number, or a chain's primary sample.
inline uint64_t drawBits(const StageContext& ctx, uint64_t key, uint32_t dim) {
  return ctx.replay ? ctx.replay->bits(key, dim) : uniformBits(key, dim);
}
// uniformFloat and uniformDouble (core/rng.h) of drawBits.
inline float drawFloat(const StageContext& ctx, uint64_t key, uint32_t dim) {
  return floatFromBits(drawBits(ctx, key, dim));
}
inline double drawDouble(const StageContext& ctx, uint64_t key, uint32_t dim) {
  return doubleFromBits(drawBits(ctx, key, dim));
}

uint64_t sampleKey(uint64_t seed, uint32_t pixel, uint32_t sample);
// The stream a sample draws from: sampleKey of the render's seed, or, replaying primary
// samples, `sample` itself: the index of the chain whose proposal it traces.
inline uint64_t sampleStream(const StageContext& ctx, uint32_t pixel, uint32_t sample) {
  return ctx.replay ? sample : sampleKey(ctx.seed, pixel, sample);
}

// Path `id` starts as sample `sample` of `pixel`: at the camera (depth 1), throughput 1, no
// radiance, no roulette or IOR factors, no recorded vertex, drawing from stream `key` (every
// bounce draws from it).
void startPath(PathQueue& paths, uint32_t id, uint64_t key, uint32_t pixel, uint32_t sample);

// Camera rays for the samples (pixel[i], sample[i]), i in range: film positions stratified
// per pixel (Latin hypercube over the pixel's samples) and importance-sampled from the pixel
// filter; replaying primary samples, uniform over the whole film (sample[i] is the chain).
// filmX/filmY (optional) receive the film positions.
void stageGenerateCameraRays(const StageContext& ctx, const uint32_t* pixel, const uint32_t* sample, RayQueue& rays,
                             IndexRange range, float* filmX = nullptr, float* filmY = nullptr);

// Seed recording: the batch's vertex history and where this bounce's vertices start (the
// vertex of slot k is base + k). vertices == nullptr: not recording.
struct VertexHistory {
  VertexQueue* vertices = nullptr;
  size_t base = 0;
};

// Path tracer: shades the hits of the live slots in range: adds MIS-weighted emission, sets
// up next-event shadow rays (contribution kept in the slot) and the next ray in place of the
// current one; clears `alive` for paths that end (escaped, absorbed, roulette, max depth).
// When recording, also writes each hit to the vertex history and notes in the slot what the
// bounce's contributions were made of.
void stageShadePath(const StageContext& ctx, PathQueue& paths, PathSlotQueue& slots, RayQueue& rays,
                    const HitQueue& hits, RayQueue& shadowRays, VertexHistory history, IndexRange range);

// Seed recording, after the shadow stage: a seed for every contribution of this bounce
// (emission found by the BSDF sample; unoccluded next-event connection), appended in slot
// order. Three steps, so that the copying runs on every thread while the store keeps that
// order: stageCountSeeds (any ranges) counts each slot's seeds and vertices, placeSeeds (once)
// turns the counts into the rows they go to and grows the store, stageRecordSeeds (any
// ranges) writes them.
struct SeedPlacement {
  // Per slot: its number of seeds, then (placeSeeds) the store row of its first seed; the
  // same for its seeds' vertices.
  std::vector<uint32_t> seed, vertex;
};
void stageCountSeeds(const PathSlotQueue& slots, const RayQueue& shadowRays, const VertexHistory& history,
                     SeedPlacement& placement, IndexRange range);
void placeSeeds(size_t live, SeedPlacement& placement, SeedStore& store);
void stageRecordSeeds(const StageContext& ctx, const PathQueue& paths, const PathSlotQueue& slots, const HitQueue& hits,
                      const RayQueue& shadowRays, const VertexHistory& history, const SeedPlacement& placement,
                      SeedStore& store, IndexRange range);

// Adds the next-event contribution of every slot whose shadow ray was not occluded.
void stageShadowResolve(const RayQueue& shadowRays, const PathSlotQueue& slots, PathQueue& paths, IndexRange range);

// Stable compaction: keeps the slots with alive != 0, in order, moving their path ids and
// rays to the front of `outSlots` / `outRays` (the per-bounce scratch columns of a slot do
// not move). Returns the number kept. `endedPaths` (optional, room for `count`) receives the
// path ids of the other slots, in order.
size_t stageCompact(const PathSlotQueue& slots, const RayQueue& rays, PathSlotQueue& outSlots, RayQueue& outRays,
                    size_t count, size_t grain, uint32_t* endedPaths = nullptr);

// Direct lighting at the first hit: adds emission seen directly, fills `shadowRays` with
// next-event rays (contribution kept in samples.shadow*) and `bsdfRays` with BSDF-sampled
// rays (weight and pdf kept in samples.bsdf*). Unused rays are disabled.
void stageShadeDirect(const StageContext& ctx, const RayQueue& cameraRays, const HitQueue& hits,
                      DirectSampleQueue& samples, RayQueue& shadowRays, RayQueue& bsdfRays, IndexRange range);

// After tracing: adds unoccluded next-event contributions and MIS-weighted emission found by
// the BSDF rays.
void stageGatherDirect(const StageContext& ctx, const RayQueue& shadowRays, const RayQueue& bsdfRays,
                       const HitQueue& bsdfHits, DirectSampleQueue& samples, IndexRange range);

}  // namespace erpt
