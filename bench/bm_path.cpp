// The wavefront path tracer: each stage alone on a captured batch, and the whole renderer,
// at 1 and 2 threads. Counters: rays/s and paths/s (samples/s).
#include <benchmark/benchmark.h>

#include "core/parallel.h"
#include "bench_support.h"
#include "erpt/render.h"
#include "stages/stages.h"
#include "tracer/tracer.h"

namespace erpt::bench {
namespace {

constexpr size_t kPaths = 1 << 16;
constexpr size_t kGrain = 512;
constexpr int kSize = 256;  // film side; kPaths = one sample for each pixel

// A batch of the Cornell box frozen at each stage's input: camera rays, their hits, the
// bounce rays that shading produced, and the shadow rays.
struct PathFixture {
  Scene scene = loadCornellBox();
  Tracer tracer{scene};
  Camera camera{scene.camera, kSize, kSize};
  PixelFilter filter{FilterKind::Box};
  LightSampler lights{scene};
  StageContext ctx{scene, camera, filter, lights, 1, kSize, kSize, 1, -1};
  PathQueue paths;
  PathSlotQueue slots, compactedSlots;
  RayQueue cameraRays, bounceRays, shadowRays, compactedRays;
  HitQueue hits, bounceHits;

  PathFixture() {
    paths.resize(kPaths);
    slots.resize(kPaths);
    compactedSlots.resize(kPaths);
    prepareRays(compactedRays, kPaths);
    prepareRays(cameraRays, kPaths);
    prepareRays(shadowRays, kPaths);
    hits.resize(kPaths);
    bounceHits.resize(kPaths);
    resetPaths();
    stageGenerateCameraRays(ctx, paths.pixel.data(), paths.sample.data(), cameraRays, {0, kPaths});
    tracer.intersect(cameraRays, hits, {0, kPaths}, RayCoherence::Coherent);
    bounceRays = cameraRays;
    stageShadePath(ctx, paths, slots, bounceRays, hits, shadowRays, {}, {0, kPaths});
  }
  void resetPaths() {
    for (size_t i = 0; i < kPaths; ++i) {
      startPath(paths, uint32_t(i), sampleKey(ctx.seed, uint32_t(i), 0), uint32_t(i), 0);
      slots.path[i] = uint32_t(i);
    }
  }
};

PathFixture& fixture() {
  static PathFixture f;
  return f;
}

void setRate(benchmark::State& state, const char* name, double perIteration) {
  state.counters[name] = benchmark::Counter(perIteration * state.iterations(), benchmark::Counter::kIsRate);
}

void BM_StageGenerate(benchmark::State& state) {
  PathFixture& f = fixture();
  ThreadPool pool(int(state.range(0)));
  RayQueue rays;
  prepareRays(rays, kPaths);
  for (auto _ : state)
    forEachRange("generate", kPaths, kGrain, [&](IndexRange r) {
      stageGenerateCameraRays(f.ctx, f.paths.pixel.data(), f.paths.sample.data(), rays, r);
    });
  setRate(state, "rays/s", kPaths);
}

void BM_StageIntersectCamera(benchmark::State& state) {
  PathFixture& f = fixture();
  ThreadPool pool(int(state.range(0)));
  RayQueue rays = f.cameraRays;
  HitQueue hits = f.hits;
  for (auto _ : state)
    forEachRange("intersect", kPaths, kGrain,
                 [&](IndexRange r) { f.tracer.intersect(rays, hits, r, RayCoherence::Coherent); });
  setRate(state, "rays/s", kPaths);
}

// The bounce rays the shade stage produced: incoherent, as in the path tracer's later
// passes. Stream call and one-by-one call on the same rays, to show the ratio.
void BM_StageIntersectBounce(benchmark::State& state) {
  PathFixture& f = fixture();
  ThreadPool pool(int(state.range(0)));
  bool stream = state.range(1) == 0;
  RayQueue rays = f.bounceRays;
  HitQueue hits = f.bounceHits;
  for (auto _ : state) {
    state.PauseTiming();
    std::copy(f.bounceRays.tfar.begin(), f.bounceRays.tfar.end(), rays.tfar.begin());
    state.ResumeTiming();
    forEachRange("intersect", kPaths, kGrain, [&](IndexRange r) {
      if (stream)
        f.tracer.intersect(rays, hits, r, RayCoherence::Incoherent);
      else
        f.tracer.intersectOneByOne(rays, hits, r);
    });
  }
  setRate(state, "rays/s", kPaths);
}

// vector:0 shades every hit through the scalar body, vector:1 plain diffuse hits in lanes.
void BM_StageShade(benchmark::State& state) {
  PathFixture& f = fixture();
  ThreadPool pool(int(state.range(0)));
  StageContext ctx = f.ctx;
  ctx.vectorShading = state.range(1) != 0;
  RayQueue rays = f.cameraRays, shadow = f.shadowRays;
  for (auto _ : state) {
    state.PauseTiming();
    f.resetPaths();
    rays = f.cameraRays;
    state.ResumeTiming();
    forEachRange("shade", kPaths, kGrain,
                 [&](IndexRange r) { stageShadePath(ctx, f.paths, f.slots, rays, f.hits, shadow, {}, r); });
  }
  setRate(state, "paths/s", kPaths);
}

void BM_StageShadow(benchmark::State& state) {
  PathFixture& f = fixture();
  ThreadPool pool(int(state.range(0)));
  RayQueue shadow = f.shadowRays;
  for (auto _ : state) {
    state.PauseTiming();
    std::copy(f.shadowRays.tfar.begin(), f.shadowRays.tfar.end(), shadow.tfar.begin());
    state.ResumeTiming();
    forEachRange("shadow", kPaths, kGrain, [&](IndexRange r) {
      f.tracer.occluded(shadow, r);
      stageShadowResolve(shadow, f.slots, f.paths, r);
    });
  }
  setRate(state, "rays/s", kPaths);
}

void BM_StageCompact(benchmark::State& state) {
  PathFixture& f = fixture();
  ThreadPool pool(int(state.range(0)));
  for (auto _ : state)
    benchmark::DoNotOptimize(stageCompact(f.slots, f.bounceRays, f.compactedSlots, f.compactedRays, kPaths, kGrain));
  setRate(state, "paths/s", kPaths);
}

// The whole renderer on the Cornell box, 256x256 at 16 spp (long enough to amortize set-up).
void BM_PathTracer(benchmark::State& state) {
  static Scene scene = loadCornellBox();
  RenderSettings s;
  s.integrator = "path";
  s.width = s.height = 256;
  s.spp = 16;
  s.threads = int(state.range(0));
  benchmarkWholeRender(state, scene, s);
}

#define THREADS ArgName("threads")->Arg(1)->Arg(2)->UseRealTime()
BENCHMARK(BM_StageGenerate)->THREADS;
BENCHMARK(BM_StageIntersectCamera)->THREADS;
BENCHMARK(BM_StageIntersectBounce)->ArgNames({"threads", "one_by_one"})->Args({1, 0})->Args({1, 1})->Args({2, 0})->Args({2, 1})->UseRealTime();
BENCHMARK(BM_StageShade)->ArgNames({"threads", "vector"})->Args({1, 0})->Args({1, 1})->Args({2, 0})->Args({2, 1})->UseRealTime();
BENCHMARK(BM_StageShadow)->THREADS;
BENCHMARK(BM_StageCompact)->THREADS;
BENCHMARK(BM_PathTracer)->THREADS->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace erpt::bench
