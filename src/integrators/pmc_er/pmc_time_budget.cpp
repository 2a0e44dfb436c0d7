// PMC-ER under `--time`: one population iterating over an open-ended stratified pool until the
// budget is used, instead of independent renders of growing spp (each repeating the training,
// the population's start and its drain). docs/pmc-er.md, "Time budgets", derives the stop rule:
//
//   The population takes pool positions round by round (a round gives every pixel one more
//   sample, in the order of that round's pixel permutation; an iteration never takes
//   positions of two rounds). At the end of each round it asks whether another round and the
//   drain still fit in the budget at the pace measured so far; if not, it drains and ends.
//   So every pixel ends with the same number R >= 1 of samples (the strata stay balanced) and
//   the image is the deposits over R, as a render of --spp R makes it. A budget shorter than
//   one round is exceeded: round 0 is always finished.
//
// The decision depends on the clock only, never on the deposits.
#include <algorithm>
#include <cmath>

#include "core/rng.h"
#include "integrators/budget_clock.h"
#include "integrators/pmc_er/pmc_er_integrator.h"
#include "integrators/pmc_er/pmc_population.h"
#include "integrators/pmc_er/stratified_pool.h"
#include "integrators/redistribution_parts.h"
#include "sample_passes.h"

namespace erpt {

namespace {
constexpr uint64_t kPoolStream = 0x706f6f6cull, kDirectChunkStream = 0x6469726368756e6bull;
// Rounds of the open-ended pool (a bound no budget reaches: 2^24 samples per pixel).
constexpr uint32_t kOpenEndedRounds = 1u << 24;

// The direct pass in chunks that keep its ratio --direct-samples / --spp to the rounds taken,
// each chunk its own stream; the image is the chunks' mean weighted by their samples. A chunk
// runs once the direct pass is behind by as many samples as it has done (so chunks double,
// and each is stratified over its own samples per pixel), and at the end to catch up.
class DirectChunks {
 public:
  DirectChunks(const Scene& scene, const RenderSettings& s) : scene_(scene), s_(s) {
    const int samples = chainOf(s).directSamples;
    perRound_ = samples > 0 ? double(samples) / double(s.spp) : 0.0;
  }
  void keepUpWith(double rounds, bool last, RenderStats& stats) {
    if (!(perRound_ > 0)) return;
    const int target = std::max(1, int(std::lround(perRound_ * rounds)));
    if (target <= done_ || (!last && target < 2 * done_)) return;
    RenderSettings chunk = s_;
    chunk.seed = streamKey(s_.seed, kDirectChunkStream, uint64_t(chunks_++));
    chainOf(chunk).directSamples = target - done_;
    const double t = budgetSeconds(s_);
    const RgbImage img = renderDirectPass(scene_, chunk, stats);
    seconds_ += budgetSeconds(s_) - t;
    if (sum_.pixels.empty()) {
      sum_.width = img.width, sum_.height = img.height;
      sum_.pixels.assign(img.pixels.size(), Color(0.0f));
    }
    for (size_t i = 0; i < img.pixels.size(); ++i) sum_.pixels[i] += img.pixels[i] * float(target - done_);
    done_ = target;
  }
  double seconds() const { return seconds_; }
  // Seconds the direct pass still needs to keep up with `rounds` (at its pace so far).
  double secondsToKeepUpWith(double rounds) const {
    if (!(perRound_ > 0) || done_ == 0) return 0;
    return std::max(0.0, perRound_ * rounds - double(done_)) * seconds_ / double(done_);
  }
  RgbImage image() const {
    RgbImage mean = sum_;
    for (Color& c : mean.pixels) c = c / float(done_);
    return mean;
  }

 private:
  const Scene& scene_;
  const RenderSettings& s_;
  double perRound_ = 0, seconds_ = 0;
  int done_ = 0, chunks_ = 0;
  RgbImage sum_;
};
// When the population may take more positions: to the end of the round in progress, and at a
// round's end one more round while it and the drain fit in the budget.
class RoundBudget {
 public:
  RoundBudget(const RenderSettings& s, const PmcSettings& p, size_t pixels, double start,
              const DirectChunks& direct)
      : s_(s), pixels_(pixels), start_(start), direct_(direct) {
    // The drain's work in iterations of the whole population: sum of (1 - r)^d over its
    // iterations (the population shrinks by 1 - r each time).
    const int drain = p.resampleRate >= 1 || p.drainRemainder >= 1
                          ? 0
                          : int(std::ceil(std::log(p.drainRemainder) / std::log(1 - p.resampleRate)));
    double drainIterations = 0;
    for (int d = 1; d <= drain; ++d) drainIterations += std::pow(1 - p.resampleRate, d);
    drainPositions_ = drainIterations * std::max(1.0, std::round(p.resampleRate * p.population));
  }

  // The prefix of the pool the population may take, having taken `taken` (PmcPopulation::run).
  size_t operator()(size_t taken) {
    const double elapsed = elapsedRendering();
    // The pace: seconds per position since the first call (which comes after the
    // population's start), without the direct pass's chunks, which are counted apart.
    const double population = elapsed - direct_.seconds();
    if (firstTaken_ == 0) firstTaken_ = taken, firstElapsed_ = population;
    if (taken > firstTaken_) perPosition_ = (population - firstElapsed_) / double(taken - firstTaken_);
    if (taken == 0 || taken % pixels_ != 0) return std::max(pixels_, (taken + pixels_ - 1) / pixels_ * pixels_);
    if (stopRequested(s_.stop)) return taken;  // interrupted: no further round
    // Without a pace yet (round 0 ended at the first call): one more round is taken.
    const double next = (double(pixels_) + drainPositions_) * perPosition_ +
                        direct_.secondsToKeepUpWith(double(taken + pixels_) / double(pixels_));
    return elapsed + next <= s_.timeBudget ? taken + pixels_ : taken;
  }
  double elapsedRendering() const { return budgetSeconds(s_) - start_ - notRendering; }

  double notRendering = 0;  // seconds spent in onPass, not counted against the budget

 private:
  const RenderSettings& s_;
  size_t pixels_;
  double start_;
  const DirectChunks& direct_;
  double drainPositions_ = 0;
  double perPosition_ = 0, firstElapsed_ = 0;
  size_t firstTaken_ = 0;
};

}  // namespace

RgbImage renderPmcForTime(const Scene& scene, const RenderSettings& s, const PmcTimeParts& parts, RenderStats& stats) {
  const PmcSettings& p = pmcOf(s);
  const size_t pixels = size_t(s.width) * size_t(s.height);
  PmcPopulation population(parts.setup,
                           PmcPopulation::Config{parts.ctx, chainSettingsOf(chainOf(s)), p, s.seed, &parts.setup.film, chainOf(s).seeds},
                           parts.mixture, stats);
  const StratifiedPool pool{uint32_t(pixels), kOpenEndedRounds, streamKey(s.seed, kPoolStream, 0)};
  DirectChunks direct(scene, s);
  RoundBudget budget(s, p, pixels, parts.start, direct);
  auto progress = [&](double) {
    if (s.progress) s.progress(std::min(1.0, budget.elapsedRendering() / s.timeBudget));
  };
  size_t reached = 0;
  auto allowed = [&](size_t taken) {
    if (taken > reached && taken % pixels == 0) {
      // A round's end: the direct pass catches up, and whoever follows the render (`erpt
      // compare`'s convergence curves) gets the image so far, the film plus what the members
      // hold (unfiltered).
      reached = taken;
      const double rounds = double(taken) / double(pixels);
      direct.keepUpWith(rounds, false, stats);
      if (s.onPass) {
        const double t = budgetSeconds(s);
        s.onPass(redistributionImage(s, population.snapshot(rounds), direct.image(), nullptr, nullptr),
                 budget.elapsedRendering(), int(rounds));
        budget.notRendering += budgetSeconds(s) - t;
      }
    }
    return budget(taken);
  };
  // Not stoppable from outside: an interrupt ends the rounds at the end of the one in
  // progress (RoundBudget) and the population drains, so the image is always a complete one.
  population.run(PoolRounds::all(pool), -1, progress, nullptr, allowed);
  const double rounds = double(population.positionsTaken()) / double(pixels);
  direct.keepUpWith(rounds, true, stats);
  stats.extraImages.emplace_back("strategy", population.strategyImage());
  const RgbImage image = redistributionImage(s, parts.setup.film.resolve(rounds), direct.image(),
                                             chainOf(s).pmFilterRadius >= 0 ? &population.proposalTally() : nullptr,
                                             &stats.extraImages);
  addChainMaps(population.tallies(), s.width, s.height, stats.extraImages);
  stats.spp = int(std::lround(rounds));  // whole rounds
  stats.partial = false;
  if (s.onPass) s.onPass(image, budget.elapsedRendering(), stats.spp);
  return image;
}

}  // namespace erpt
