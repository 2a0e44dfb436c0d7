// Raw Embree throughput through the project's Tracer: stream calls (rtcIntersectNp /
// rtcOccludedNp on the SoA columns) against one-ray-at-a-time calls on the same rays, at 1
// and 2 threads. Compare with shared/measurements/embree-limits.md.
#include <benchmark/benchmark.h>

#include "bench_support.h"
#include "core/parallel.h"
#include "tracer/tracer.h"

namespace erpt::bench {
namespace {

constexpr size_t kRays = 1 << 18;
constexpr size_t kChunk = 1024;

struct TraceFixture {
  Scene scene = loadCornellBox();
  Tracer tracer{scene};
  RayQueue primary = makeRays(scene, RaySet::Primary, kRays);
  RayQueue diffuse = makeRays(scene, RaySet::Diffuse, kRays);
  RayQueue shadow = makeRays(scene, RaySet::Shadow, kRays);
};

TraceFixture& fixture() {
  static TraceFixture f;
  return f;
}

enum Api { kStream, kOneByOne };

void runIntersect(benchmark::State& state, RaySet set) {
  TraceFixture& f = fixture();
  Api api = Api(state.range(0));
  ThreadPool pool(int(state.range(1)));
  RayQueue source = set == RaySet::Primary ? f.primary : f.diffuse;
  RayQueue rays = source;
  HitQueue hits;
  hits.resize(kRays);
  RayCoherence coherence = set == RaySet::Primary ? RayCoherence::Coherent : RayCoherence::Incoherent;
  for (auto _ : state) {
    state.PauseTiming();
    std::copy(source.tfar.begin(), source.tfar.end(), rays.tfar.begin());
    state.ResumeTiming();
    forEachRange("intersect", kRays, kChunk, [&](IndexRange r) {
      if (api == kStream)
        f.tracer.intersect(rays, hits, r, coherence);
      else
        f.tracer.intersectOneByOne(rays, hits, r);
    });
  }
  state.counters["rays/s"] = benchmark::Counter(double(kRays) * state.iterations(), benchmark::Counter::kIsRate);
}

void BM_IntersectPrimary(benchmark::State& state) { runIntersect(state, RaySet::Primary); }
void BM_IntersectDiffuse(benchmark::State& state) { runIntersect(state, RaySet::Diffuse); }

void BM_OccludedShadow(benchmark::State& state) {
  TraceFixture& f = fixture();
  Api api = Api(state.range(0));
  ThreadPool pool(int(state.range(1)));
  RayQueue rays = f.shadow;
  for (auto _ : state) {
    state.PauseTiming();
    std::copy(f.shadow.tfar.begin(), f.shadow.tfar.end(), rays.tfar.begin());
    state.ResumeTiming();
    forEachRange("occluded", kRays, kChunk, [&](IndexRange r) {
      if (api == kStream)
        f.tracer.occluded(rays, r);
      else
        f.tracer.occludedOneByOne(rays, r);
    });
  }
  state.counters["rays/s"] = benchmark::Counter(double(kRays) * state.iterations(), benchmark::Counter::kIsRate);
}

// Args: {api (0 stream, 1 one-by-one), threads}
#define TRACE_ARGS ArgNames({"api", "threads"})->Args({0, 1})->Args({1, 1})->Args({0, 2})->Args({1, 2})->UseRealTime()
BENCHMARK(BM_IntersectPrimary)->TRACE_ARGS;
BENCHMARK(BM_IntersectDiffuse)->TRACE_ARGS;
BENCHMARK(BM_OccludedShadow)->TRACE_ARGS;

}  // namespace
}  // namespace erpt::bench
