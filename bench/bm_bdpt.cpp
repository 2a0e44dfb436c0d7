// BDPT's stages on the Cornell box (256x256 film, one sample per pixel for 16,384 pixels, in
// chunks of 2048 as the integrator runs them), at 1 and 2 threads: the light and camera walks
// (rays/s: intersect and extend per bounce), the connections (connections/s, and shadow rays/s
// of their occlusion stream), and the whole renderer (rays/s, samples/s, each stage's share).
#include <benchmark/benchmark.h>

#include <atomic>
#include <memory>
#include <mutex>

#include "bench_support.h"
#include "core/parallel.h"
#include "erpt/render.h"
#include "integrators/bdpt/bdpt_wavefront.h"

namespace erpt::bench {
namespace {

constexpr int kSize = 256;
constexpr size_t kChunk = 2048, kChunks = 8;

struct BdptFixture {
  Scene scene = loadCornellBox();
  Tracer tracer{scene};
  Camera camera{scene.camera, kSize, kSize};
  PixelFilter filter{FilterKind::Box};  // BDPT's camera samples are uniform in the pixel
  LightSampler lights{scene};
  StageContext stage{scene, camera, filter, lights, 1, kSize, kSize, 1, -1};
  BdptContext ctx{stage, kSize};
  std::vector<std::unique_ptr<BdptWavefront>> chunks;

  BdptFixture() {
    for (size_t c = 0; c < kChunks; ++c) {
      chunks.push_back(std::make_unique<BdptWavefront>());
      start(c);
    }
  }
  // Chunk c's samples (pixels c * kChunk ...), ready to walk.
  void start(size_t c) {
    BdptWavefront& w = *chunks[c];
    w.prepare(kChunk);
    for (size_t j = 0; j < kChunk; ++j) {
      w.paths.pixel[j] = uint32_t(c * kChunk + j);
      w.paths.sample[j] = 0;
    }
  }
};

BdptFixture& fixture() {
  static BdptFixture f;
  return f;
}

// Walks every chunk's subpaths of `side` (light first: the camera walk comes after it).
uint64_t walkAll(BdptFixture& f, BdptSide side, StageTimes& times) {
  std::atomic<uint64_t> rays{0};
  forEachRange("walk", kChunks, 1, [&](IndexRange r) {
    for (size_t c = r.begin; c < r.end; ++c) {
      StageTimes own;
      if (side == BdptSide::Light) f.start(c);
      rays += walkSubpaths(f.tracer, f.ctx, side, *f.chunks[c], kChunk, own);
    }
  }, &times);
  return rays;
}

void walkBenchmark(benchmark::State& state, BdptSide side) {
  BdptFixture& f = fixture();
  ThreadPool pool(int(state.range(0)));
  double rays = 0;
  StageTimes times;
  for (auto _ : state) {
    if (side == BdptSide::Camera) {
      state.PauseTiming();
      walkAll(f, BdptSide::Light, times);
      state.ResumeTiming();
    }
    rays += double(walkAll(f, side, times));
  }
  state.counters["rays/s"] = benchmark::Counter(rays, benchmark::Counter::kIsRate);
}

void BM_BdptLightWalk(benchmark::State& state) { walkBenchmark(state, BdptSide::Light); }
void BM_BdptCameraWalk(benchmark::State& state) { walkBenchmark(state, BdptSide::Camera); }

// Every strategy of the walked chunks: forming the connections, then their shadow stream.
void BM_BdptConnect(benchmark::State& state) {
  BdptFixture& f = fixture();
  ThreadPool pool(int(state.range(0)));
  StageTimes setup;
  walkAll(f, BdptSide::Light, setup);
  walkAll(f, BdptSide::Camera, setup);
  double rays = 0, connections = 0, connectSeconds = 0, shadowSeconds = 0;
  std::mutex m;
  for (auto _ : state) {
    forEachRange("connect", kChunks, 1, [&](IndexRange r) {
      for (size_t c = r.begin; c < r.end; ++c) {
        StageTimes own;
        const uint64_t traced = connectSubpaths(f.tracer, f.ctx, *f.chunks[c], kChunk, own);
        std::lock_guard<std::mutex> lock(m);
        rays += double(traced);
        connections += double(f.chunks[c]->connections.size());
        for (const auto& [name, t] : own.all()) (name == "connect" ? connectSeconds : shadowSeconds) += t;
      }
    });
  }
  const double threads = double(state.range(0));
  state.counters["connections/s"] = benchmark::Counter(connections, benchmark::Counter::kIsRate);
  state.counters["connect_per_thread/s"] = connections / connectSeconds;
  state.counters["shadow_rays_per_thread/s"] = rays / shadowSeconds;
  state.counters["threads"] = threads;
}

// The whole renderer, 256x256 at 4 spp.
void BM_Bdpt(benchmark::State& state) {
  static Scene scene = loadCornellBox();
  RenderSettings s;
  s.integrator = "bdpt";
  s.width = s.height = kSize;
  s.spp = 4;
  s.threads = int(state.range(0));
  benchmarkWholeRender(state, scene, s, "samples/s");
}

#define THREADS ArgName("threads")->Arg(1)->Arg(2)->UseRealTime()
BENCHMARK(BM_BdptLightWalk)->THREADS->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BdptCameraWalk)->THREADS->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BdptConnect)->THREADS->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Bdpt)->THREADS->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace erpt::bench
