// `--integrator path`: the wavefront path tracer (BSDF importance sampling, next-event
// estimation with MIS, Russian roulette). It is also the Monte Carlo seed sampler of ERPT.
//
// Samples are processed in batches of paths. Each bounce runs the stages
//   intersect -> shade -> shadow (occlusion stream) -> compact
// over the live slots only, until no path of the batch is left; then the batch's radiance
// goes to the film in path order, so the image does not depend on the thread count.
#include <atomic>
#include <chrono>

#include "erpt/film.h"
#include "erpt/film_splat.h"
#include "erpt/stages.h"
#include "erpt/tracer.h"
#include "path_integrator.h"
#include "render_setup.h"

namespace erpt {

namespace {
constexpr size_t kBatchPaths = 1 << 17;
constexpr size_t kGrain = 512;

void initPaths(PathQueue& paths, PathSlotQueue& slots, const PathSampleSet& samples, size_t first, IndexRange r) {
  for (size_t i = r.begin; i < r.end; ++i) {
    samples.at(first + i, paths.pixel[i], paths.sample[i]);
    paths.runIndex[i] = uint32_t(first + i);
    paths.depth[i] = 1;
    paths.throughputSet(i, Color(1.0f));
    paths.radianceSet(i, Color(0.0f));
    paths.prevPdf[i] = 0;
    paths.pLength[i] = 1;
    paths.lastVertex[i] = -1;
    slots.path[i] = uint32_t(i);
  }
}

// Seed recording: vertex i of the history is the eye of path i.
void writeEyeVertices(VertexQueue& history, PathQueue& paths, Vec3 eye, IndexRange r) {
  VertexQueue::Row v;  // kind kEyeVertex, no material, no emitter, no parent
  v.p = eye;
  v.pdfForward = 1;  // the camera ray: density of the film position (filter-sampled)
  for (size_t i = r.begin; i < r.end; ++i) {
    history.setRow(i, v);
    paths.lastVertex[i] = int32_t(i);
  }
}
}  // namespace

void tracePathSamples(const RenderSetup& setup, const PathSampleSet& samples, const PathTraceOutput& out,
                      RenderStats& stats) {
  const Tracer& tracer = setup.tracer;
  const StageContext& ctx = setup.ctx;
  const size_t total = samples.count;
  PathQueue paths;
  PathSlotQueue slots[2];
  RayQueue rays[2], shadowRays;
  HitQueue hits;
  VertexQueue history;
  std::atomic<uint64_t> rayCount{0};
  uint64_t invalid = 0;

  for (size_t first = 0; first < total; first += kBatchPaths) {
    const size_t n = std::min(kBatchPaths, total - first);
    paths.resize(n);
    for (int b = 0; b < 2; ++b) {
      slots[b].resize(n);
      prepareRays(rays[b], n);
    }
    prepareRays(shadowRays, n);
    hits.resize(n);
    int cur = 0;
    const bool recording = out.seeds != nullptr;
    if (recording) history.resize(n);
    forEachRange("generate", n, kGrain, [&](IndexRange r) {
      initPaths(paths, slots[cur], samples, first, r);
      stageGenerateCameraRays(ctx, paths.pixel.data(), paths.sample.data(), rays[cur], r, paths.filmX.data(),
                              paths.filmY.data());
      if (recording) writeEyeVertices(history, paths, setup.camera.position(), r);
    }, &stats.stages);

    VertexHistory bounceHistory{recording ? &history : nullptr, n};
    for (size_t live = n, bounce = 0; live > 0; ++bounce) {
      if (recording) history.resize(bounceHistory.base + live);
      RayCoherence coherence = bounce == 0 ? RayCoherence::Coherent : RayCoherence::Incoherent;
      rayCount += live;
      forEachRange("intersect", live, kGrain,
                   [&](IndexRange r) { tracer.intersect(rays[cur], hits, r, coherence); }, &stats.stages);
      forEachRange("shade", live, kGrain,
                   [&](IndexRange r) {
                     stageShadePath(ctx, paths, slots[cur], rays[cur], hits, shadowRays, bounceHistory, r);
                   },
                   &stats.stages);
      forEachRange("shadow", live, kGrain, [&](IndexRange r) {
        uint64_t traced = 0;
        for (size_t k = r.begin; k < r.end; ++k) traced += shadowRays.tnear[k] <= shadowRays.tfar[k];
        rayCount += traced;
        tracer.occluded(shadowRays, r);
        stageShadowResolve(shadowRays, slots[cur], paths, r);
      }, &stats.stages);
      auto start = std::chrono::steady_clock::now();
      if (recording) {
        stageRecordSeeds(ctx, paths, slots[cur], hits, shadowRays, bounceHistory, live, *out.seeds);
        stats.stages.add("record seeds", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        start = std::chrono::steady_clock::now();
      }
      bounceHistory.base += live;
      live = stageCompact(slots[cur], rays[cur], slots[1 - cur], rays[1 - cur], live, kGrain);
      stats.stages.add("compact", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      cur = 1 - cur;
    }

    for (size_t i = 0; i < n; ++i) {
      const Color L = paths.radianceAt(i);
      invalid += !isFinite(L);
      if (out.film) out.film->addIfFinite(paths.pixel[i], L);
    }
    if (out.splat) {
      auto start = std::chrono::steady_clock::now();
      out.splat->addSamples(paths.filmX.data(), paths.filmY.data(), paths.radianceR.data(), paths.radianceG.data(),
                            paths.radianceB.data(), n);
      stats.stages.add("splat", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    if (recording && out.seedSink) {
      out.seedSink(*out.seeds);
      out.seeds->clear();
    }
    if (out.progress) out.progress(double(first + n) / double(total));
  }
  stats.samples += total;
  stats.rays += rayCount;
  stats.invalidSamples += invalid;
}

RgbImage renderPath(const Scene& scene, const RenderSettings& settings, RenderStats& stats) {
  RenderSetup setup(scene, settings);
  const std::vector<uint32_t>& order = setup.order;
  const size_t spp = size_t(settings.spp);
  // Sample k: pixel order[k / spp], its sample k % spp (a pixel's samples are neighbours).
  const PathSampleSet samples{setup.totalSamples, [&](size_t k, uint32_t& pixel, uint32_t& sample) {
                                pixel = order[k / spp];
                                sample = uint32_t(k % spp);
                              }};
  if (setup.filmMode != FilmMode::Fis) {
    SplatFilm splat(setup.filter, settings.width, settings.height);
    PathTraceOutput out{nullptr, &splat, settings.seeds, settings.seedSink, settings.progress};
    tracePathSamples(setup, samples, out, stats);
    return splat.resolve(setup.filmMode, double(spp));
  }
  tracePathSamples(setup, samples, PathTraceOutput{&setup.film, nullptr, settings.seeds, settings.seedSink, settings.progress},
                   stats);
  return setup.film.resolve(double(spp));
}

}  // namespace erpt
