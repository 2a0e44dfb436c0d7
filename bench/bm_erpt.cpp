// ERPT: each chain-step stage alone on a full chain queue of the Cornell box, and the whole
// chain loop, at 1 and 2 threads. Counters: mutations/s, rays/s; the loop also reports the
// share of its time spent inside Embree (intersect and occlusion stages).
#include <benchmark/benchmark.h>

#include "bench_support.h"
#include "stages/chain_step.h"
#include "integrators/chain_lanes.h"
#include "erpt/render.h"
#include "core/rng.h"

namespace erpt::bench {
namespace {

constexpr int kSize = 128;
constexpr size_t kSlots = 1 << 13;
constexpr size_t kGrain = 256;

// Seeds of a 4 spp path-traced Cornell box and the chain queues (StepQueues, kSlots slots)
// with chains started from them and stepped once, plus snapshots of the queues before each
// stage.
struct ErptFixture : StepQueues {
  Scene scene = loadCornellBox();
  Tracer tracer{scene};
  Camera camera{scene.camera, kSize, kSize};
  PixelFilter filter{FilterKind::Box};
  LightSampler lights{scene};
  FilmDensity density{filter, kSize, kSize};
  StepConfig ctx{MeasureContext{scene, lights, camera, density}, StepSettings{}};
  SeedStore seeds;
  RayQueue eyeRays, tracedShadowRays;
  ProposalQueue mutated, walked;  // proposals after mutate, after walk + connect
  double energy = 0;  // sum of seed luminances

  ErptFixture() : StepQueues(kSlots) {
    RenderSettings s;
    s.width = s.height = kSize;
    s.spp = 4;
    s.seed = 5;
    s.filterSet = true;
    s.seeds = &seeds;
    RenderStats stats;
    render(scene, s, stats);
    for (size_t i = 0; i < seeds.size(); ++i) energy += luminance(seeds.contribution(i));
    for (size_t slot = 0, i = 0; slot < kSlots; ++i)
      if (seeds.seeds.vertexCount[i] <= uint32_t(kMaxChainVertices) && luminance(seeds.contribution(i)) > 0)
        loadChainFromSeed(chains, chainVertices, slot++, seeds, i, streamKey(1, i, 0), 1 << 30, 0.01f);
    // One whole step first: a chain's f(y) and fixed tail are cached from its first step on,
    // so the stages below see chains as they are for every step but a chain's first.
    StepCounters warmUp;
    ChainStep{tracer, ctx, nullptr, kGrain}.run(*this, warmUp);
    const IndexRange all{0, kSlots};
    stageChainMutate(ctx, chains, chainVertices, proposals, rays, all);
    for (size_t i = 0; i < kSlots; ++i) disableRay(shadowRays, i);
    eyeRays = rays;
    mutated = proposals;
    tracer.intersect(rays, hits, all, RayCoherence::Incoherent);
    stageChainTrace(ctx, chains, chainVertices, proposals, proposalVertices, rays, hits, shadowRays, all);
    walked = proposals;
    tracedShadowRays = shadowRays;
    stageChainConnect(tracer, tracedShadowRays, walked, all);
  }
};

ErptFixture& fixture() {
  static ErptFixture f;
  return f;
}

void setRate(benchmark::State& state, const char* name, double perIteration) {
  state.counters[name] = benchmark::Counter(perIteration * double(state.iterations()), benchmark::Counter::kIsRate);
}

size_t enabledRays(const RayQueue& r) {
  size_t n = 0;
  for (size_t i = 0; i < r.size(); ++i) n += r.tnear[i] <= r.tfar[i];
  return n;
}

void BM_ErptMutate(benchmark::State& state) {
  ErptFixture& f = fixture();
  ThreadPool pool(int(state.range(0)));
  ProposalQueue proposals = f.proposals;
  RayQueue rays = f.rays;
  for (auto _ : state)
    forEachRange("mutate", kSlots, kGrain, [&](IndexRange r) {
      stageChainMutate(f.ctx, f.chains, f.chainVertices, proposals, rays, r);
    });
  setRate(state, "mutations/s", kSlots);
}

void BM_ErptIntersect(benchmark::State& state) {
  ErptFixture& f = fixture();
  ThreadPool pool(int(state.range(0)));
  RayQueue rays = f.eyeRays;
  HitQueue hits = f.hits;
  const size_t n = enabledRays(f.eyeRays);
  for (auto _ : state) {
    state.PauseTiming();
    std::copy(f.eyeRays.tfar.begin(), f.eyeRays.tfar.end(), rays.tfar.begin());
    state.ResumeTiming();
    forEachRange("intersect", kSlots, kGrain,
                 [&](IndexRange r) { f.tracer.intersect(rays, hits, r, RayCoherence::Incoherent); });
  }
  setRate(state, "rays/s", double(n));
}

void BM_ErptTrace(benchmark::State& state) {
  ErptFixture& f = fixture();
  ThreadPool pool(int(state.range(0)));
  ProposalQueue proposals = f.mutated;
  RayQueue rays = f.eyeRays, shadow = f.shadowRays;
  VertexQueue vertices = f.proposalVertices;
  HitQueue hits = f.hits;
  {
    const IndexRange all{0, kSlots};
    f.tracer.intersect(rays, hits, all, RayCoherence::Incoherent);
  }
  const RayQueue traced = rays;
  for (auto _ : state) {
    state.PauseTiming();
    proposals = f.mutated;
    rays = traced;
    state.ResumeTiming();
    forEachRange("trace", kSlots, kGrain, [&](IndexRange r) {
      stageChainTrace(f.ctx, f.chains, f.chainVertices, proposals, vertices, rays, hits, shadow, r);
    });
  }
  setRate(state, "mutations/s", kSlots);
}

void BM_ErptConnect(benchmark::State& state) {
  ErptFixture& f = fixture();
  ThreadPool pool(int(state.range(0)));
  RayQueue shadow = f.shadowRays;
  ProposalQueue proposals = f.walked;
  const size_t n = enabledRays(f.shadowRays);
  for (auto _ : state) {
    state.PauseTiming();
    std::copy(f.shadowRays.tfar.begin(), f.shadowRays.tfar.end(), shadow.tfar.begin());
    state.ResumeTiming();
    forEachRange("connect", kSlots, kGrain, [&](IndexRange r) {
      stageChainConnect(f.tracer, shadow, proposals, r);
    });
  }
  setRate(state, "rays/s", double(n));
}

void BM_ErptAccept(benchmark::State& state) {
  ErptFixture& f = fixture();
  ThreadPool pool(int(state.range(0)));
  ChainQueue chains = f.chains;
  VertexQueue vertices = f.chainVertices;
  ProposalQueue proposals = f.walked;
  DepositQueue deposits = f.deposits;
  StepCounters counters;
  for (auto _ : state) {
    state.PauseTiming();
    chains = f.chains;
    vertices = f.chainVertices;
    state.ResumeTiming();
    forEachRange("accept", kSlots, kGrain, [&](IndexRange r) {
      stageChainAccept(f.ctx, chains, vertices, proposals, f.proposalVertices, deposits, counters, r);
    });
  }
  setRate(state, "mutations/s", kSlots);
}

void BM_ErptDeposit(benchmark::State& state) {
  ErptFixture& f = fixture();
  ChainQueue chains = f.chains;
  VertexQueue vertices = f.chainVertices;
  ProposalQueue proposals = f.walked;
  DepositQueue deposits = f.deposits;
  StepCounters counters;
  stageChainAccept(f.ctx, chains, vertices, proposals, f.proposalVertices, deposits, counters, {0, kSlots});
  Film film(kSize, kSize);
  // Argument 1: both noise filters on (consecutive samples at 10, proposal tally).
  std::vector<uint32_t> tally(size_t(kSize) * kSize, 0);
  for (auto _ : state) {
    DepositFilters filters;
    if (state.range(0) == 1) {
      filters.maxConsecutive = 10;
      filters.proposalTally = &tally;
      // The same records every iteration: restart the runs, or every chain would look stuck.
      state.PauseTiming();
      std::fill(chains.runLength.begin(), chains.runLength.end(), 0u);
      state.ResumeTiming();
    }
    benchmark::DoNotOptimize(applyDeposits(chains, proposals, deposits, IndexRange{0, kSlots}, f.density, film, filters));
  }
  setRate(state, "deposits/s", kSlots);
}

// The whole chain loop (refill, mutate, intersect, trace, connect, accept, deposit) on the
// fixture's seeds: 16 mutations per pixel in chains of 100 steps, one lane per thread as in a
// render. Second argument: the chain slots of each lane, 0 for what a render uses
// (kErptLaneSlots), else that many.
void BM_ErptChainLoop(benchmark::State& state) {
  ErptFixture& f = fixture();
  const int threads = int(state.range(0));
  ThreadPool pool(threads);
  const size_t slots = state.range(1) > 0 ? size_t(state.range(1)) : kErptLaneSlots;
  StepConfig ctx = f.ctx;
  ChainSettings lanes;
  lanes.chainLength = 100;
  lanes.directSamples = -1;  // every seed is ERPT's
  ChainLanes::Config config{ctx, lanes, 7, slots};
  config.lanes = threads;
  config.depositEnergy = f.energy / (kSize * kSize * 16.0);
  uint64_t mutations = 0, rays = 0;
  double embree = 0, serial = 0, total = 0;
  for (auto _ : state) {
    Film film(kSize, kSize);
    ChainStats stats;
    StageTimes times;
    ChainLanes chains(f.tracer, config, film, stats, times);
    chains.consume(f.seeds);
    chains.finish();
    mutations += stats.mutations;
    rays += stats.rays;
    for (const auto& [name, seconds] : times.all()) {
      total += seconds;
      if (name == "chain intersect" || name == "chain connect") embree += seconds;
      // The single-threaded part: the per-seed triage of each seed batch (which seeds start
      // chains, how many). Refill and deposit run in every lane.
      if (name == "chain seed triage") serial += seconds;
    }
  }
  state.counters["mutations/s"] = benchmark::Counter(double(mutations), benchmark::Counter::kIsRate);
  state.counters["rays/s"] = benchmark::Counter(double(rays), benchmark::Counter::kIsRate);
  state.counters["embree_share"] = total > 0 ? embree / total : 0;
  state.counters["serial_share"] = total > 0 ? serial / total : 0;
}

// One whole chain step (ChainStep::run: mutate, intersect, trace, connect, accept) on the
// fixture's chains with one mutation kind only (argument: MutationKind; chains the kind cannot
// mutate make no proposal), at 1 and 2 threads.
void BM_ErptChainStep(benchmark::State& state) {
  ErptFixture& f = fixture();
  const MutationKind kind = MutationKind(state.range(0));
  ThreadPool pool(int(state.range(1)));
  StepConfig ctx = f.ctx;
  const bool lens = kind == MutationKind::Lens || kind == MutationKind::LensDisk;
  ctx.settings.strategy = lens ? MutationStrategy::LensOnly : MutationStrategy::CausticOnly;
  ctx.settings.lensShape = kind == MutationKind::LensDisk ? LensShape::Disk : LensShape::Square;
  ctx.settings.causticAngle = kind == MutationKind::CausticVeach ? CausticAngle::Veach : CausticAngle::Erpt;
  StepQueues q = f;
  StepCounters counters;
  const ChainStep step{f.tracer, ctx, nullptr, kGrain};
  uint64_t rays = 0;
  for (auto _ : state) rays += step.run(q, counters);
  state.SetLabel(mutationName(kind));
  setRate(state, "mutations/s", double(counters.proposed[size_t(kind)]) / double(state.iterations()));
  state.counters["rays/s"] = benchmark::Counter(double(rays), benchmark::Counter::kIsRate);
}

#define THREADS ArgName("threads")->Arg(1)->Arg(2)->UseRealTime()
BENCHMARK(BM_ErptMutate)->THREADS;
BENCHMARK(BM_ErptIntersect)->THREADS;
BENCHMARK(BM_ErptTrace)->THREADS;
BENCHMARK(BM_ErptConnect)->THREADS;
BENCHMARK(BM_ErptAccept)->THREADS;
BENCHMARK(BM_ErptDeposit)->Arg(0)->Arg(1)->UseRealTime();
BENCHMARK(BM_ErptChainStep)
    ->ArgNames({"kind", "threads"})
    ->ArgsProduct({{int(MutationKind::Lens), int(MutationKind::LensDisk), int(MutationKind::Caustic),
                    int(MutationKind::CausticVeach)},
                   {1, 2}})
    ->UseRealTime();
BENCHMARK(BM_ErptChainLoop)
    ->ArgNames({"threads", "slots"})
    ->Args({1, 0})
    ->Args({2, 0})
    ->Args({1, 2048})
    ->Args({2, 2048})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace erpt::bench
