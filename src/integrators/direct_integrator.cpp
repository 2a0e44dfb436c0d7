// `--integrator direct`: direct illumination (emission seen directly, plus one bounce of
// light via next-event estimation and BSDF sampling combined with the power heuristic), as
// Mitsuba's `direct` integrator computes it. Kept as a debugging integrator.
//
// Wavefront layout: samples are processed in batches; each batch runs the stages
// generate -> intersect (coherent) -> shade -> {occluded, intersect} -> gather -> film.
#include <atomic>

#include "direct_integrator.h"
#include "erpt/film.h"
#include "erpt/stages.h"
#include "erpt/tracer.h"
#include "render_setup.h"

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
  const std::vector<uint32_t>& order = setup.order;
  const size_t spp = size_t(settings.spp), total = setup.totalSamples;
  DirectSampleQueue samples;
  RayQueue cameraRays, shadowRays, bsdfRays;
  HitQueue cameraHits, bsdfHits;
  std::atomic<uint64_t> rays{0};
  uint64_t invalid = 0;

  for (size_t batchStart = 0; batchStart < total; batchStart += kBatchSamples) {
    const size_t n = std::min(kBatchSamples, total - batchStart);
    for (auto* q : {&cameraRays, &shadowRays, &bsdfRays}) prepareRays(*q, n);
    for (auto* q : {&cameraHits, &bsdfHits}) q->resize(n);
    samples.resize(n);
    // Slot j of the batch is sample (batchStart + j) % spp of pixel order[(batchStart + j) / spp].
    for (size_t j = 0; j < n; ++j) {
      samples.pixel[j] = order[(batchStart + j) / spp];
      samples.sample[j] = uint32_t((batchStart + j) % spp);
    }
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
    for (size_t j = 0; j < n; ++j) {
      invalid += !film.addIfFinite(samples.pixel[j], samples.radianceAt(j));
    }
    if (settings.progress) settings.progress(double(batchStart + n) / double(total));
  }
  stats.samples = total;
  stats.rays = rays;
  stats.invalidSamples = invalid;
  return film.resolve(double(spp));
}

}  // namespace erpt
