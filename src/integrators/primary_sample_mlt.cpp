// Primary-sample-space Metropolis light transport, shared by `pssmlt` (Kelemen, Szirmay-Kalos,
// Antal and Csonka 2002, as Mitsuba 0.6's, over the path tracer or BDPT) and `mmlt`
// (Hachisuka, Kaplanyan and Dachsbacher 2014, "Multiplexed Metropolis light transport", as
// pbrt-v4's `mlt`): docs/pssmlt.md.
//
//   0. pssmlt, optional (--direct-samples N, default 64): paths of at most two segments go to
//      a direct pass of the sampler (as Mitsuba's `directSamples`); the chains hold the rest.
//   1. Bootstrap (--bootstrap N samples per pixel; by default sized as MLT's): samples of fresh
//      primary vectors (mmlt: that many for each path length, each with one BDPT strategy
//      drawn from the vector, its contribution times the number of strategies). Their mean
//      luminance is b (mmlt: the sum over the lengths of each length's mean).
//   2. Chains (--chains C): each starts from a bootstrap sample resampled in proportion to its
//      luminance (systematic resampling; its vector is replayed once to become the chain's
//      state; mmlt: the chain keeps that sample's path length), then takes L = M pixels / C
//      steps (M: --mutations-per-pixel): a large step (every number afresh) with probability
//      --large-step-prob, else a small step of every number the sample read (pssmlt:
//      Kelemen's offset, --small-step; mmlt: a normal offset, --sigma).
//   3. Every step deposits expected values at the current and the proposed sample: pssmlt
//      with Kelemen's weights, (1 - a) / (f / b + p) and (a + [large]) / (f' / b + p); mmlt
//      as pbrt-v4, (1 - a) b / f and a b / f'; a = min(1, f' / f), f the luminance.
// The chains of a group (kGroupChains) step together on one thread: each step's proposals
// are one wavefront of the sampler's stages, drawing their numbers from the chains' vectors
// (StageContext::replay). Deposits go to an ExactFilm, so the image is the same for any
// thread count.
#include "integrators/primary_sample_mlt.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <numeric>

#include "core/parallel.h"
#include "core/rng.h"
#include "erpt/chain_options.h"
#include "erpt/error.h"
#include "integrators/bdpt/bdpt_wavefront.h"
#include "integrators/mlt/mlt_integrator.h"
#include "integrators/seed_sampler.h"
#include "integrators/path/path_integrator.h"
#include "integrators/redistribution_parts.h"
#include "integrators/systematic_resampling.h"
#include "integrators/chain_options.h"
#include "integrators/sample_passes.h"
#include "kernels/primary_samples.h"
#include "models/exact_film.h"
#include "models/film_density.h"
#include "render_setup.h"

namespace erpt {

namespace {
constexpr uint64_t kBootstrapStream = 0x7073626f6f74ull, kResampleStream = 0x70737265736dull,
                   kChainStream = 0x707373746570ull, kDirectStream = 0x707364697265ull;
// Chains stepped together by one task: one wavefront of proposals per step.
constexpr size_t kGroupChains = 256;
// Dimensions of a step's stream that the path tracer never reads: the step's two coins.
constexpr uint32_t kDimLargeCoin = 0x7ffffff0u, kDimAcceptCoin = 0x7ffffff1u;
// A chain's vector takes about 2 KB (primary_samples.h): a million chains, 2 GB.
constexpr int kMaxPssmltChains = 1 << 20;
constexpr double kMaxBootstrapSamples = double(1u << 30);
// mmlt's longest path in segments when --max-depth is unbounded (pbrt-v4's maxdepth 5: five
// bounces), and the most it takes (a chain's path length is a byte). Numbers of bounces past
// the kept slots (15) are drawn afresh by every proposal (primary_samples.h).
constexpr int kMmltDefaultLongestPath = 6, kMmltMaxLongestPath = 255;

double secondsSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// One splat of a sample: the radiance it brings to a film position. A path-tracer sample has
// one; a BDPT sample has its camera strategies' sum and each light-tracing connection's.
struct Splat {
  float x, y;
  Color c;
};

// The samples of a group's proposals: proposal k's splats are splats[begin[k], begin[k + 1]),
// its target value f (the luminance of all of them) is value[k], and invalid[k] says it had a
// value that was not finite (the proposal is then rejected with f = 0).
struct ProposalSamples {
  std::vector<Splat> splats;
  std::vector<uint32_t> begin;
  std::vector<double> value;
  std::vector<uint8_t> invalid;
  void start(size_t n) {
    splats.clear();
    begin.assign(1, 0);
    value.assign(n, 0.0);
    invalid.assign(n, 0);
  }
  void add(size_t k, float x, float y, Color c) {
    if (!isFinite(c)) invalid[k] = 1;
    else if (!isBlack(c)) splats.push_back({x, y, c});
  }
  // Closes proposal k's list (proposals close in order), its splats scaled by `scale`.
  void close(size_t k, float scale = 1) {
    begin.push_back(uint32_t(splats.size()));
    if (scale != 1)
      for (uint32_t i = begin[k]; i < begin[k + 1]; ++i) splats[i].c = splats[i].c * scale;
    double f = 0;
    for (uint32_t i = begin[k]; i < begin[k + 1]; ++i) f += std::max(0.0, double(luminance(splats[i].c)));
    value[k] = invalid[k] ? 0.0 : f;
  }
};

// One task's tracing memory: the path tracer's or BDPT's queues, and a group's results.
struct GroupScratch {
  PathTracerScratch tracer;
  BdptWavefront bdpt;
  std::vector<uint8_t> large;  // this step's kind, by chain of the group
  std::vector<uint32_t> chains;
  std::vector<float> x, y;
  std::vector<Color> radiance;
  ProposalSamples proposals;
};

// Traces the proposals of chains [first, first + n) of `samples` on the calling thread, by the
// path tracer or by BDPT, into g.proposals. With `segments` (mmlt, BDPT only), chain c's sample
// is one strategy of a path of segments[c] segments, drawn from its vector, its contribution
// times the number of strategies. Returns the rays traced.
uint64_t traceProposals(const RenderSetup& setup, SeedSampler sampler, PrimarySamples& samples, size_t first, size_t n,
                        const uint8_t* segments, GroupScratch& g, StageTimes& times) {
  StageContext ctx = setup.ctx;
  ctx.replay = &samples;
  ProposalSamples& out = g.proposals;
  out.start(n);
  if (sampler == SeedSampler::Path) {
    g.chains.resize(n);
    std::iota(g.chains.begin(), g.chains.end(), uint32_t(first));
    g.x.resize(n), g.y.resize(n), g.radiance.resize(n);
    const uint64_t rays = traceReplayedSamples(setup.tracer, ctx, g.chains.data(), n, g.tracer, times, g.x.data(),
                                               g.y.data(), g.radiance.data());
    for (size_t k = 0; k < n; ++k) {
      out.add(k, g.x[k], g.y[k], g.radiance[k]);
      out.close(k);
    }
    return rays;
  }
  // BDPT: both subpaths, every strategy, then each sample's camera strategies at its film
  // position and its light tracing where it lands (connections are made sample by sample).
  const BdptContext bctx{ctx, ctx.height, -1, -1, false};
  BdptWavefront& w = g.bdpt;
  w.prepare(n);
  for (size_t k = 0; k < n; ++k) w.paths.pixel[k] = 0, w.paths.sample[k] = uint32_t(first + k);
  if (segments) {
    // s + t = segments + 1 vertices, t >= 1: segments + 1 strategies, one drawn per sample
    // (a 64-bit multiply-shift: each is off 1 / strategies by less than 2^-60).
    w.paths.strategyS.resize(n);
    w.paths.strategyT.resize(n);
    for (size_t k = 0; k < n; ++k) {
      const uint64_t strategies = uint64_t(segments[first + k]) + 1;
      const uint64_t u = drawBits(ctx, first + k, kDimBdptStrategy);
      const int sv = int((unsigned __int128)u * strategies >> 64);
      w.paths.strategyS[k] = int16_t(sv);
      w.paths.strategyT[k] = int16_t(strategies - uint64_t(sv));
    }
  }
  uint64_t rays = walkSubpaths(setup.tracer, bctx, BdptSide::Light, w, n, times);
  rays += walkSubpaths(setup.tracer, bctx, BdptSide::Camera, w, n, times);
  rays += connectSubpaths(setup.tracer, bctx, w, n, times);
  const auto start = std::chrono::steady_clock::now();
  const size_t m = w.connections.size();
  for (size_t c = 0; c < m; ++c)
    if (w.shadowRays.tfar[c] >= 0 && !w.connections.toCamera[c]) w.radiance[w.connections.sample[c]] += w.connections.valueAt(c);
  size_t c = 0;
  for (size_t k = 0; k < n; ++k) {
    out.add(k, w.paths.filmX[k], w.paths.filmY[k], w.radiance[k]);
    for (; c < m && w.connections.sample[c] == k; ++c)
      if (w.shadowRays.tfar[c] >= 0 && w.connections.toCamera[c])
        out.add(k, w.connections.filmX[c], w.connections.filmY[c], w.connections.valueAt(c));
    out.close(k, segments ? float(segments[first + k] + 1) : 1.0f);
  }
  times.add("resolve", secondsSince(start));
  return rays;
}

// Stage times of the tasks, in seconds of the whole pool (thread time / threads).
class PoolTimes {
 public:
  PoolTimes(StageTimes& to, int threads) : to_(to), threads_(double(threads)) {}
  void add(const StageTimes& task) {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& [stage, seconds] : task.all()) to_.add(stage, seconds / threads_);
  }

 private:
  StageTimes& to_;
  double threads_;
  std::mutex mutex_;
};

uint64_t bootstrapKey(uint64_t seed, size_t sample) { return streamKey(seed, kBootstrapStream, sample); }

// The bootstrap: the target value of `count` samples of fresh primary vectors; with
// `segments` (mmlt), sample i is of segments[i] segments.
std::vector<double> runBootstrap(const RenderSetup& setup, SeedSampler sampler, uint64_t seed, size_t count,
                                 const std::vector<uint8_t>* segments, PoolTimes& times, std::atomic<uint64_t>& rays,
                                 std::atomic<uint64_t>& invalid) {
  struct Scratch {
    // Large steps only: the step size is unused.
    PrimarySamples samples{kGroupChains, 1.0, true};
    GroupScratch group;
  };
  std::vector<double> values(count);
  PerThread<Scratch> local;
  forEachRange("pssmlt bootstrap", (count + kGroupChains - 1) / kGroupChains, 1, [&](IndexRange groups) {
    StageTimes taskTimes;
    Scratch& s = local.local();
    for (size_t g = groups.begin; g < groups.end; ++g) {
      const size_t first = g * kGroupChains, n = std::min(kGroupChains, count - first);
      for (size_t k = 0; k < n; ++k) s.samples.propose(k, bootstrapKey(seed, first + k), true);
      rays += traceProposals(setup, sampler, s.samples, 0, n, segments ? segments->data() + first : nullptr, s.group,
                             taskTimes);
      for (size_t k = 0; k < n; ++k) {
        values[first + k] = s.group.proposals.value[k];
        invalid += s.group.proposals.invalid[k];
      }
    }
    times.add(taskTimes);
  });
  return values;
}

// The chains' current samples, by chain: their splats and target value f.
// A rejected proposal leaves the current sample where it is, so its deposits only add to one
// weight (`pending`), splatted once when the chain leaves the sample or stops: one splat per
// accepted sample instead of one per step.
struct ChainSamples {
  std::vector<std::vector<Splat>> splats;
  std::vector<double> value, pending;
  explicit ChainSamples(size_t n) : splats(n), value(n), pending(n) {}
  void take(size_t c, const ProposalSamples& p, size_t k) {
    splats[c].assign(p.splats.begin() + p.begin[k], p.splats.begin() + p.begin[k + 1]);
    value[c] = p.value[k];
  }
  // Deposits chain c's pending weight at its current sample.
  template <class Deposit>
  void flush(size_t c, const Deposit& deposit) {
    if (pending[c] > 0)
      for (const Splat& sp : splats[c]) deposit(sp.x, sp.y, sp.c, pending[c]);
    pending[c] = 0;
  }
};

struct GroupCounts {
  uint64_t small = 0, smallAccepted = 0, large = 0, largeAccepted = 0, invalid = 0, steps = 0;
};

// --direct-samples N: paths of at most two segments by the path tracer stopped there, N
// samples per pixel, its own stream. Its film splats uniform samples as the chains' does
// (unbiased splatting), so that both estimate the same filtered image at the borders too.
RgbImage renderDirectPart(const Scene& scene, const RenderSettings& s, RenderStats& stats) {
  RenderSettings direct = subRenderSettings(s);
  direct.integrator = "path";
  direct.spp = chainOf(s).directSamples;
  direct.seed = streamKey(s.seed, kDirectStream, 0);
  direct.maxDepth = s.maxDepth < 0 ? 2 : std::min(2, s.maxDepth);
  RenderStats directStats;
  // BDPT's film is unbiased splatting already.
  RgbImage image = chainOf(s).seeds == SeedSampler::Bdpt ? renderWithSeedSampler(scene, direct, directStats)
                                                         : renderPath(scene, direct, directStats, FilmMode::SplatUnbiased);
  stats.rays += directStats.rays;
  for (const auto& [name, seconds] : directStats.stages.all()) stats.stages.add("direct " + name, seconds);
  return image;
}

}  // namespace

int mmltLongestPath(const RenderSettings& s) { return s.maxDepth >= 0 ? s.maxDepth : kMmltDefaultLongestPath; }

void validatePrimarySampleMlt(const RenderSettings& s, bool multiplexed) {
  const std::string name = multiplexed ? "mmlt" : "pssmlt";
  validateChainOptions(chainOf(s));
  const MltSettings& m = mltOf(s);
  if (m.chains > kMaxPssmltChains)
    throw UsageError("--chains " + std::to_string(m.chains) + " is more than " + name + "'s " +
                     std::to_string(kMaxPssmltChains) + " (each chain keeps a vector of 2 to 4 KB)");
  const double pixels = double(s.width) * double(s.height);
  const double lengths = multiplexed ? mmltLongestPath(s) : 1;
  if (double(std::max(m.bootstrapSpp, 1)) * pixels * lengths > kMaxBootstrapSamples)
    throw UsageError("--bootstrap x pixels" + std::string(multiplexed ? " x path lengths (--max-depth)" : "") +
                     " gives more than 2^30 bootstrap samples");
  if (multiplexed && s.maxDepth > kMmltMaxLongestPath)
    throw UsageError("--max-depth " + std::to_string(s.maxDepth) + " is more than mmlt's " +
                     std::to_string(kMmltMaxLongestPath) + " segments (a chain keeps its path length in a byte)");
  if (s.share.split()) throw UsageError(name + " does not split a render over processes");
  if (s.resume || s.onPasses) throw UsageError(name + " does not write checkpoints or partial images");
}

namespace {

// The bootstrap: samples of fresh primary vectors drawn from `seed`'s stream, their values
// and (mmlt) path lengths, and b.
struct PrimarySampleBootstrap {
  uint64_t seed = 0;
  std::vector<double> values;
  std::vector<uint8_t> segments;  // mmlt: sample i's path length in segments
  size_t perLength = 0;           // samples of each path length (pssmlt: all)
  double b = 0;                   // the sum over the path lengths of each one's mean value
  double seconds = 0;
  uint64_t rays = 0, invalid = 0;
};

// pssmlt with --direct-samples: a direct pass renders paths of one and two segments.
bool hasDirectPass(const RenderSettings& s, bool multiplexed) { return !multiplexed && chainOf(s).directSamples > 0; }

// 1. The bootstrap (mmlt: as many samples for each path length, 1 to the longest, as
// pbrt-v4's: a length with few samples gets b_k, and so its share of the chains, from a
// handful of paths). A bootstrap sample costs what a chain step does (the same sampler, the
// same strategies), so MLT's rule gives as many per pixel as the chains take steps, at most
// 100,000 in all (per length for mmlt): Mitsuba's and pbrt-v4's size.
PrimarySampleBootstrap takeBootstrap(const RenderSetup& setup, const RenderSettings& s, bool multiplexed,
                                     StageTimes& stages) {
  const auto start = std::chrono::steady_clock::now();
  PrimarySampleBootstrap boot;
  boot.seed = s.seed;
  const size_t pixels = size_t(s.width) * size_t(s.height);
  boot.perLength =
      size_t(bootstrapSamplesPerPixel(mltOf(s), double(pixels), chainOf(s).mutationsPerPixel, 1.0)) * pixels;
  const int lengths = multiplexed ? mmltLongestPath(s) : 1;
  if (multiplexed)
    for (int k = 1; k <= lengths; ++k) boot.segments.insert(boot.segments.end(), boot.perLength, uint8_t(k));
  PoolTimes times(stages, setup.pool.threads());
  std::atomic<uint64_t> rays{0}, invalid{0};
  const SeedSampler sampler = multiplexed ? SeedSampler::Bdpt : chainOf(s).seeds;
  boot.values = runBootstrap(setup, sampler, s.seed, boot.perLength * size_t(lengths),
                             multiplexed ? &boot.segments : nullptr, times, rays, invalid);
  boot.b = std::accumulate(boot.values.begin(), boot.values.end(), 0.0) / double(boot.perLength);
  boot.rays = rays, boot.invalid = invalid;
  boot.seconds = secondsSince(start);
  return boot;
}

// The bootstrap's statistics, added to a render's.
void addBootstrapStats(const PrimarySampleBootstrap& boot, RenderStats& stats) {
  PssmltStats& ps = pssmltStatsOf(stats);
  ps.b = boot.b;
  ps.bootstrapSamples += boot.values.size();
  ps.bootstrapSeconds += boot.seconds;
  ps.rays += boot.rays;
  stats.samples += boot.values.size();
  stats.rays += boot.rays;
  stats.invalidSamples += boot.invalid;
}

// The bootstrap's and the chains' paths then have three segments or more.
void keepOffDirectPaths(RenderSetup& setup, const RenderSettings& s, bool multiplexed) {
  if (hasDirectPass(s, multiplexed)) setup.ctx.minSegments = 3;
}

}  // namespace

RgbImage renderPrimarySampleMlt(const Scene& scene, const RenderSettings& s, RenderStats& stats, bool multiplexed) {
  validatePrimarySampleMlt(s, multiplexed);
  PssmltStats& ps = pssmltStatsOf(stats);
  const MltSettings& m = mltOf(s);
  const SeedSampler sampler = multiplexed ? SeedSampler::Bdpt : chainOf(s).seeds;
  const RgbImage direct = hasDirectPass(s, multiplexed) ? renderDirectPart(scene, s, stats) : RgbImage{};
  RenderSetup setup(scene, s);
  keepOffDirectPaths(setup, s, multiplexed);
  const size_t pixels = size_t(s.width) * size_t(s.height);
  const double mutationsPerPixel = chainOf(s).mutationsPerPixel;
  PoolTimes times(stats.stages, setup.pool.threads());
  std::atomic<uint64_t> rays{0};
  const PrimarySampleBootstrap boot = takeBootstrap(setup, s, multiplexed, stats.stages);
  addBootstrapStats(boot, stats);
  const double b = boot.b;
  ps.b = b;
  const std::vector<uint8_t>& bootSegments = boot.segments;
  if (s.progress) s.progress(0.05);

  // 2. The chains' starts: bootstrap samples resampled by their value, replayed into the chains.
  const size_t chains = size_t(m.chains);
  const uint64_t length = uint64_t(std::ceil(mutationsPerPixel * double(pixels) / double(chains)));
  ExactFilm film(s.width, s.height, std::max(b, 1e-30) * 0x1p-24, true);
  const FilmDensity density(setup.filter, s.width, s.height, true);  // film positions uniform over the image
  std::atomic<uint64_t> stepsDone{0};
  GroupCounts total;
  if (b > 0) {
    const std::vector<size_t> picks =
        systematicPicks(boot.values, chains, uniformDouble(streamKey(s.seed, kResampleStream, 0), 0));
    PrimarySamples primary(chains, multiplexed ? pssmltOf(s).sigma : pssmltOf(s).smallStep,
                           sampler == SeedSampler::Bdpt, multiplexed ? StepKind::Normal : StepKind::Kelemen);
    ChainSamples current(chains);
    // mmlt: each chain keeps the path length of the bootstrap sample it started from.
    std::vector<uint8_t> chainSegments;
    if (multiplexed)
      for (size_t c = 0; c < chains; ++c) chainSegments.push_back(bootSegments[picks[c]]);
    const uint8_t* segments = multiplexed ? chainSegments.data() : nullptr;
    const uint64_t chainSeed = streamKey(s.seed, kChainStream, 0);
    const size_t groups = (chains + kGroupChains - 1) / kGroupChains;
    std::vector<GroupCounts> counts(groups);
    PerThread<GroupScratch> local;
    std::mutex progressMutex;
    const auto chainStart = std::chrono::steady_clock::now();

    // Kelemen's weights (pssmlt) or plain expected values (mmlt, as pbrt-v4).
    const double pLarge = multiplexed ? 0.0 : m.largeStepProbability;
    const double largeWeight = multiplexed ? 0.0 : 1.0;
    const auto deposit = [&](float x, float y, Color c, double weight) {
      density.splat(x, y, [&](uint32_t pixel, float w) { film.add(pixel, c, float(weight) * w); });
    };
    forEachRange("chains", groups, 1, [&](IndexRange range) {
      StageTimes taskTimes;
      GroupScratch& g = local.local();
      for (size_t group = range.begin; group < range.end; ++group) {
        const size_t first = group * kGroupChains, n = std::min(kGroupChains, chains - first);
        GroupCounts& count = counts[group];
        for (size_t k = 0; k < n; ++k) primary.propose(first + k, bootstrapKey(boot.seed, picks[first + k]), true);
        rays += traceProposals(setup, sampler, primary, first, n, segments, g, taskTimes);
        for (size_t k = 0; k < n; ++k) {
          primary.accept(first + k);
          current.take(first + k, g.proposals, k);  // f > 0: the bootstrap's value, replayed
        }
        for (uint64_t t = 0; t < length; ++t) {
          if (stopRequested(s.stop)) break;
          const auto start = std::chrono::steady_clock::now();
          g.large.resize(n);
          for (size_t k = 0; k < n; ++k) {
            const uint64_t key = streamKey(chainSeed, first + k, t);
            g.large[k] = uniformDouble(key, kDimLargeCoin) < m.largeStepProbability;
            primary.propose(first + k, key, g.large[k]);
          }
          taskTimes.add("propose", secondsSince(start));
          rays += traceProposals(setup, sampler, primary, first, n, segments, g, taskTimes);
          const auto accepting = std::chrono::steady_clock::now();
          const ProposalSamples& p = g.proposals;
          for (size_t k = 0; k < n; ++k) {
            const size_t c = first + k;
            const uint64_t key = streamKey(chainSeed, c, t);
            const bool large = g.large[k];
            const double f = current.value[c], proposed = p.value[k];
            count.invalid += p.invalid[k];
            const double a = f > 0 ? std::min(1.0, proposed / f) : 1.0;
            // Expected values with Kelemen's weights (docs/pssmlt.md): the chain's estimate and
            // the large steps' own Monte Carlo estimate, combined by the balance heuristic.
            const double kept = (1 - a) / (f / b + pLarge), moved = (a + (large ? largeWeight : 0)) / (proposed / b + pLarge);
            if (f > 0 && kept > 0) current.pending[c] += kept;
            if (proposed > 0 && moved > 0)
              for (uint32_t i = p.begin[k]; i < p.begin[k + 1]; ++i) deposit(p.splats[i].x, p.splats[i].y, p.splats[i].c, moved);
            const bool accepted = uniformDouble(key, kDimAcceptCoin) < a;
            (large ? count.large : count.small) += 1;
            (large ? count.largeAccepted : count.smallAccepted) += accepted;
            if (!accepted) continue;
            primary.accept(c);
            current.flush(c, deposit);
            current.take(c, p, k);
          }
          taskTimes.add("accept and deposit", secondsSince(accepting));
          count.steps += n;
          const uint64_t done = stepsDone += n;
          if (s.progress && t % 16 == 15) {
            std::lock_guard<std::mutex> lock(progressMutex);
            s.progress(0.05 + 0.95 * double(done) / (double(chains) * double(length)));
          }
        }
        for (size_t k = 0; k < n; ++k) current.flush(first + k, deposit);
      }
      times.add(taskTimes);
    });
    ps.chainSeconds = secondsSince(chainStart);
    for (const GroupCounts& c : counts) {
      total.small += c.small, total.smallAccepted += c.smallAccepted;
      total.large += c.large, total.largeAccepted += c.largeAccepted;
      total.invalid += c.invalid, total.steps += c.steps;
    }
  }
  ps.chains = chains;
  ps.chainLength = length;
  ps.smallSteps = total.small, ps.smallAccepted = total.smallAccepted;
  ps.largeSteps = total.large, ps.largeAccepted = total.largeAccepted;
  ps.invalidProposals = total.invalid;
  ps.rays += rays;
  stats.rays += rays;
  stats.invalidSamples += total.invalid;

  // 3. The image: every step deposited luminance b in all; the mean over the steps per pixel.
  RgbImage image;
  image.width = s.width, image.height = s.height;
  image.pixels.assign(pixels, Color(0.0f));
  const bool complete = b == 0 || stepsDone == uint64_t(chains) * length;
  stats.spp = complete ? 1 : 0;
  if (!complete) {
    stats.partial = true;
    stats.keptSpp = std::max(1e-9, double(s.spp) * double(stepsDone) / (double(chains) * double(length)));
  }
  if (stepsDone > 0) film.addTo(image, double(stepsDone) / double(pixels));
  for (size_t i = 0; i < direct.pixels.size(); ++i) image.pixels[i] += direct.pixels[i];
  return image;
}

}  // namespace erpt
