// PMC-ER throughput: whole renders of the Cornell box (128x128, 4 spp, box filter, every path
// by PMC-ER) at 1 and 2 threads, per flow. Counters: chain-loop mutations per second
// (mutations / time in the iterations' chain steps), the whole render's mutations per second,
// and the shares of the render's time spent resampling, regenerating (tracing pool positions
// with the wavefront path tracer and making candidates) and training (region table).
#include <benchmark/benchmark.h>

#include "erpt/erpt_settings.h"
#include "erpt/pmc_settings.h"
#include "bench_support.h"
#include "erpt/render.h"

namespace erpt::bench {
namespace {

void BM_PmcRender(benchmark::State& state) {
  static const Scene scene = loadCornellBox();
  RenderSettings s;
  s.integrator = "pmc-er";
  s.width = s.height = 128;
  s.spp = 4;
  s.filterSet = true;
  s.filter = FilterKind::Box;
  s.threads = int(state.range(0));
  pmcOf(s).flow = state.range(1) ? PmcFlow::Balance : PmcFlow::EqualDeposition;
  chainOf(s).directSamples = -1;
  uint64_t mutations = 0;
  double seconds = 0, chain = 0, resample = 0, regenerate = 0, train = 0;
  for (auto _ : state) {
    RenderStats stats;
    render(scene, s, stats);
    mutations += chainStatsOf(stats).mutations;
    seconds += stats.seconds;
    chain += pmcStatsOf(stats).chainSeconds;
    resample += pmcStatsOf(stats).resampleSeconds;
    regenerate += pmcStatsOf(stats).regenerateSeconds;
    train += pmcStatsOf(stats).trainSeconds;
  }
  state.SetLabel(state.range(1) ? "balance" : "equal-deposition");
  state.counters["chain_mutations/s"] = chain > 0 ? double(mutations) / chain : 0;
  state.counters["mutations/s"] = benchmark::Counter(double(mutations), benchmark::Counter::kIsRate);
  state.counters["resample_share"] = seconds > 0 ? resample / seconds : 0;
  state.counters["regenerate_share"] = seconds > 0 ? regenerate / seconds : 0;
  state.counters["train_share"] = seconds > 0 ? train / seconds : 0;
}

BENCHMARK(BM_PmcRender)
    ->ArgNames({"threads", "balance"})
    ->ArgsProduct({{1, 2}, {0, 1}})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace erpt::bench
