// MLT throughput: whole renders of the Cornell box (128x128, box filter, 64 mutations per
// pixel, MLT's defaults otherwise) at 1 and 2 threads, with large-step probabilities 0.3 (the
// default) and 0.1. Counters: chain-loop mutations per second, the whole render's mutations per
// second, the chains' rays per second, and the shares of the render's time spent in the
// bootstrap and in the large steps (their path-tracer samples and proposals).
#include <benchmark/benchmark.h>

#include "erpt/erpt_settings.h"
#include "erpt/mlt_settings.h"
#include "bench_support.h"
#include "erpt/render.h"

namespace erpt::bench {
namespace {

void BM_MltRender(benchmark::State& state) {
  static const Scene scene = loadCornellBox();
  RenderSettings s;
  s.integrator = "mlt";
  s.width = s.height = 128;
  s.spp = 1;
  s.filterSet = true;
  s.filter = FilterKind::Box;
  s.threads = int(state.range(0));
  mltOf(s).largeStepProbability = float(state.range(1)) / 10.0f;
  chainOf(s).mutationsPerPixel = 64;
  uint64_t mutations = 0, rays = 0;
  double seconds = 0, chain = 0, bootstrap = 0, large = 0;
  for (auto _ : state) {
    RenderStats stats;
    render(scene, s, stats);
    mutations += chainStatsOf(stats).mutations;
    rays += chainStatsOf(stats).rays;
    seconds += stats.seconds;
    chain += mltStatsOf(stats).chainSeconds;
    bootstrap += mltStatsOf(stats).bootstrapSeconds;
    const auto& stages = stats.stages.all();
    if (const auto it = stages.find("chain large step"); it != stages.end()) large += it->second;
  }
  state.counters["chain_mutations/s"] = chain > 0 ? double(mutations) / chain : 0;
  state.counters["chain_rays/s"] = chain > 0 ? double(rays) / chain : 0;
  state.counters["mutations/s"] = benchmark::Counter(double(mutations), benchmark::Counter::kIsRate);
  state.counters["bootstrap_share"] = seconds > 0 ? bootstrap / seconds : 0;
  state.counters["large_step_share"] = seconds > 0 ? large / seconds : 0;
}

BENCHMARK(BM_MltRender)
    ->ArgNames({"threads", "large_step_tenths"})
    ->ArgsProduct({{1, 2}, {3, 1}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace erpt::bench
