#pragma once

#include <atomic>
#include <functional>
#include <memory>

#include "erpt/integrators.h"
#include "erpt/render.h"

namespace erpt {

struct RenderSetup;
struct StageContext;
struct SeedStore;
class StageTimes;
class Film;
class SplatFilm;
class Tracer;

// `settings` must be resolved (resolveSettings). `film`: how samples reach the image (Fis for
// every path tracer inside another integrator; `--integrator path` passes its --film).
RgbImage renderPath(const Scene& scene, const RenderSettings& settings, RenderStats& stats,
                    FilmMode film = FilmMode::Fis);
IntegratorModule pathModule();

// The samples one run of the wavefront path tracer takes: sample k of [0, count) is sample
// number `sample` of pixel `pixel` (its stratum, stages.h). renderPath takes every pixel's
// spp samples; PMC-ER's stratified pool hands out its positions a batch at a time.
struct PathSampleSet {
  size_t count = 0;
  std::function<void(size_t k, uint32_t& pixel, uint32_t& sample)> at;
};
struct PathTracerScratch;
// Where a run's results go: radiance to `film` (when set), contributions as seeds to
// `seeds` (when set; with `seedSink`, streamed batch by batch and cleared).
struct PathTraceOutput {
  Film* film = nullptr;
  SplatFilm* splat = nullptr;  // instead of `film`: every sample splatted over its filter
  SeedStore* seeds = nullptr;
  std::function<void(SeedStore&)> seedSink;
  std::function<void(double fraction)> progress;
  const std::atomic<bool>* stop = nullptr;  // checked before every batch
  // Seed recording's working memory, kept by the caller from run to run (a sample pass each):
  // allocated afresh for every run, its first touch of every page showed as a tenth of an
  // ERPT render's time (docs/performance.md). Without it, the run allocates its own.
  PathTracerScratch* scratch = nullptr;
};
// The end of one batch of a sampler's run: its seeds (in out.seeds) go to out.seedSink and are
// cleared, and the progress is reported (`done` of `total` samples). Adds a finished run's
// counts to `stats`.
void deliverBatch(const PathTraceOutput& out, size_t done, size_t total);
void addRunCounts(RenderStats& stats, uint64_t samples, uint64_t rays, uint64_t invalid);

// Runs the path tracer over `samples` with the setup's camera, lights and stage context (its
// spp sets the strata); adds samples, rays and invalid samples to `stats`. Returns false if
// out.stop turned true before every batch was done (what the batches done added stays).
bool tracePathSamples(const RenderSetup& setup, const PathSampleSet& samples, const PathTraceOutput& out,
                      RenderStats& stats);

// The path tracer's working memory for seed recording (traceSeedsInline: one per thread;
// PathTraceOutput::scratch), reused from run to run.
struct PathTracerScratch {
  PathTracerScratch();
  ~PathTracerScratch();
  struct Impl;
  std::unique_ptr<Impl> impl;
};
// Runs the path tracer over `samples` on the calling thread only, with stage context `ctx`
// (its seed keys the samples' random streams), and appends every contribution to `seeds` in
// the usual order (bounce, sample). For callers that already run one task per thread: MLT's
// large steps inside a chain lane. Returns the rays traced.
uint64_t traceSeedsInline(const Tracer& tracer, const StageContext& ctx, const PathSampleSet& samples, SeedStore& seeds,
                          PathTracerScratch& scratch, StageTimes& times);

// Replaying primary samples (ctx.replay set): one path-tracer sample for each of the chains
// chains[0..n), drawn from its proposal, on the calling thread; its film position and
// radiance go to filmX[k], filmY[k], radiance[k]. Returns the rays traced.
uint64_t traceReplayedSamples(const Tracer& tracer, const StageContext& ctx, const uint32_t* chains, size_t n,
                              PathTracerScratch& scratch, StageTimes& times, float* filmX, float* filmY, Color* radiance);

}  // namespace erpt
