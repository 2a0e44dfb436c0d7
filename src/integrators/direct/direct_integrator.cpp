// `--integrator direct`: direct illumination (emission seen directly, plus one bounce of
// light via next-event estimation and BSDF sampling combined with the power heuristic), as
// Mitsuba's `direct` integrator computes it. Kept as a debugging integrator.
//
// Wavefront layout: samples are processed in sample passes (sample_passes.h), in batches; each batch runs the stages
// generate -> intersect (coherent) -> shade -> {occluded, intersect} -> gather -> film.
#include <atomic>

#include "core/parallel.h"
#include "integrators/direct/direct_integrator.h"
#include "models/film.h"
#include "stages/stages.h"
#include "tracer/tracer.h"
#include "render_setup.h"
#include "sample_passes.h"

namespace erpt {

namespace {
constexpr size_t kBatchSamples = 1 << 16;
constexpr size_t kGrain = 256;
}  // namespace

RgbImage renderDirect(const Scene& scene, const RenderSettings& settings, RenderStats& stats) {
  RenderSetup setup(scene, settings);
  const Tracer& tracer = setup.tracer;
  const StageContext& ctx = setup.ctx;
  Film& film = setup.film;
  DirectSampleQueue samples;
  RayQueue cameraRays, shadowRays, bsdfRays;
  HitQueue cameraHits, bsdfHits;
  // Renders the samples of passes [first, end) in batches.
  auto run = [&](int first, int end, const std::function<void(double)>& progress) {
    const PathSampleSet set = passSamples(setup.order, first, end, settings.share);
    const size_t total = set.count;
    std::atomic<uint64_t> rays{0};
    for (size_t batchStart = 0; batchStart < total; batchStart += kBatchSamples) {
      if (stopRequested(settings.stop)) return false;
      const size_t n = std::min(kBatchSamples, total - batchStart);
      for (auto* q : {&cameraRays, &shadowRays, &bsdfRays}) prepareRays(*q, n);
      for (auto* q : {&cameraHits, &bsdfHits}) q->resize(n);
      samples.resize(n);
      for (size_t j = 0; j < n; ++j) set.at(batchStart + j, samples.pixel[j], samples.sample[j]);
      forEachRange("generate", n, kGrain, [&](IndexRange r) { stageGenerateCameraRays(ctx, samples.pixel.data(), samples.sample.data(), cameraRays, r); },
                   &stats.stages);
      forEachRange("intersect", n, kGrain,
                   [&](IndexRange r) { tracer.intersect(cameraRays, cameraHits, r, RayCoherence::Coherent); },
                   &stats.stages);
      forEachRange("shade", n, kGrain,
                   [&](IndexRange r) { stageShadeDirect(ctx, cameraRays, cameraHits, samples, shadowRays, bsdfRays, r); },
                   &stats.stages);
      forEachRange("shadow", n, kGrain, [&](IndexRange r) { tracer.occluded(shadowRays, r); }, &stats.stages);
      forEachRange("intersect", n, kGrain,
                   [&](IndexRange r) { tracer.intersect(bsdfRays, bsdfHits, r, RayCoherence::Incoherent); },
                   &stats.stages);
      forEachRange("gather", n, kGrain,
                   [&](IndexRange r) {
                     uint64_t count = 0;
                     for (size_t i = r.begin; i < r.end; ++i)
                       count += 1 + (shadowRays.tnear[i] <= shadowRays.tfar[i]) + (bsdfRays.tnear[i] <= bsdfRays.tfar[i]);
                     rays += count;
                     stageGatherDirect(ctx, shadowRays, bsdfRays, bsdfHits, samples, r);
                   },
                   &stats.stages);
      // Accumulate in slot order on one thread: film sums are then independent of threading.
      for (size_t j = 0; j < n; ++j) stats.invalidSamples += !film.addIfFinite(samples.pixel[j], samples.radianceAt(j));
      stats.samples += n;
      stats.rays += rays.exchange(0);
      progress(double(batchStart + n) / double(total));
    }
    return true;
  };
  SamplePassHooks passes;
  setFilmStateHooks(passes, film, stats);
  passes.run = run;
  passes.image = [&](int done) { return film.resolve(double(done)); };
  return renderInSamplePasses(settings, setup.order.size(), stats, passes);
}

IntegratorModule directModule() {
  IntegratorModule m;
  m.name = "direct";
  m.description = "direct lighting only (next-event estimation and BSDF sampling with MIS, as Mitsuba's), for debugging";
  m.samplePasses = true;
  m.validate = [](const RenderSettings&) {};
  m.render = renderDirect;
  return m;
}

}  // namespace erpt
