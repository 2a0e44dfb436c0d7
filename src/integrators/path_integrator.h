#pragma once

#include <atomic>
#include <functional>

#include "erpt/render.h"

namespace erpt {

struct RenderSetup;
class Film;
class SplatFilm;

// `settings` must be resolved (resolveSettings).
RgbImage renderPath(const Scene& scene, const RenderSettings& settings, RenderStats& stats);

// The samples one run of the wavefront path tracer takes: sample k of [0, count) is sample
// number `sample` of pixel `pixel` (its stratum, stages.h). renderPath takes every pixel's
// spp samples; PMC-ER's stratified pool hands out its positions a batch at a time.
struct PathSampleSet {
  size_t count = 0;
  std::function<void(size_t k, uint32_t& pixel, uint32_t& sample)> at;
};
// Where a run's results go: radiance to `film` (when set), contributions as seeds to
// `seeds` (when set; with `seedSink`, streamed batch by batch and cleared).
struct PathTraceOutput {
  Film* film = nullptr;
  SplatFilm* splat = nullptr;  // instead of `film`: every sample splatted over its filter
  SeedStore* seeds = nullptr;
  std::function<void(SeedStore&)> seedSink;
  std::function<void(double fraction)> progress;
  const std::atomic<bool>* stop = nullptr;  // checked before every batch
};
// Runs the path tracer over `samples` with the setup's camera, lights and stage context (its
// spp sets the strata); adds samples, rays and invalid samples to `stats`. Returns false if
// out.stop turned true before every batch was done (what the batches done added stays).
bool tracePathSamples(const RenderSetup& setup, const PathSampleSet& samples, const PathTraceOutput& out,
                      RenderStats& stats);

}  // namespace erpt
