// PMC-ER under `--time`: one population iterating over an open-ended stratified pool until the
// budget is used, instead of independent renders of growing spp (each repeating the training,
// the population's start and its drain). docs/pmc-er.md, "Time budgets", derives the stop rule:
//
//   The population takes pool positions round by round (a round gives every pixel one more
//   sample, in the order of that round's pixel permutation). Before it starts a round it asks
//   whether the round, the drain and the direct pass's share still fit in the budget at the
//   measured speed; a round once started is finished, so every pixel ends with the same number
//   R >= 1 of samples (the strata stay balanced) and the image is the deposits over R, as a
//   render of --spp R would make it. A budget shorter than one round is exceeded: round 0 is
//   always finished (stopping inside it would leave part of the pixels unsampled, and the
//   members' energy no longer a multiple of f: docs/pmc-er.md).
//
// The decision depends on the clock only, never on the deposits.
#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/rng.h"
#include "integrators/pmc_er/pmc_er_integrator.h"
#include "integrators/pmc_er/pmc_population.h"
#include "integrators/pmc_er/stratified_pool.h"
#include "integrators/redistribution_parts.h"
#include "sample_passes.h"

namespace erpt {

namespace {
using Clock = std::chrono::steady_clock;
constexpr uint64_t kPoolStream = 0x706f6f6cull, kDirectRestStream = 0x64697265637432ull;
// Rounds of the open-ended pool (a bound no budget reaches: 2^24 samples per pixel).
constexpr uint32_t kOpenEndedRounds = 1u << 24;

double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// When the population may take more positions: rounds whole while the next one fits.
class RoundBudget {
 public:
  RoundBudget(const RenderSettings& s, const PmcSettings& p, size_t pixels, Clock::time_point start, double directPerRound,
              double directSecondsPerSpp)
      : s_(s), pixels_(pixels), start_(start), directPerRound_(directPerRound), directSecondsPerSpp_(directSecondsPerSpp) {
    // The drain's work in iterations of the whole population: sum of (1 - r)^d over its
    // iterations (the population shrinks by 1 - r each time).
    const int drain = p.resampleRate >= 1 || p.drainRemainder >= 1
                          ? 0
                          : int(std::ceil(std::log(p.drainRemainder) / std::log(1 - p.resampleRate)));
    for (int d = 1; d <= drain; ++d) drainIterations_ += std::pow(1 - p.resampleRate, d);
    positionsPerIteration_ = std::max(1.0, std::round(p.resampleRate * p.population));
  }

  // The prefix of the pool the population may take, having taken `taken` (PmcPopulation::run).
  size_t operator()(size_t taken) {
    const double elapsed = secondsSince(start_);
    // Seconds per position at the current pace: from the iterations since the last call
    // (the first call also counts the population's start, so it waits for the second).
    if (lastTaken_ > 0 && taken > lastTaken_) perPosition_ = (elapsed - lastElapsed_) / double(taken - lastTaken_);
    lastTaken_ = taken, lastElapsed_ = elapsed;
    // The end of the round in progress (round 0 at least): always finished.
    const size_t boundary = std::max<size_t>(pixels_, (taken + pixels_ - 1) / pixels_ * pixels_);
    if (stopRequested(s_.stop)) return boundary;  // interrupted: no further round
    if (perPosition_ > 0 && fits(boundary + pixels_, taken, elapsed)) return boundary + pixels_;
    return boundary;
  }

 private:
  // Whether taking positions up to `upTo`, then the drain and the rest of the direct pass,
  // ends within the budget.
  bool fits(size_t upTo, size_t taken, double elapsed) const {
    const double population = double(upTo - taken) * perPosition_;
    const double drain = drainIterations_ * positionsPerIteration_ * perPosition_;
    const double direct = std::max(0.0, directPerRound_ * double(upTo) / double(pixels_) - 1) * directSecondsPerSpp_;
    return elapsed + population + drain + direct <= s_.timeBudget;
  }

  const RenderSettings& s_;
  size_t pixels_;
  Clock::time_point start_;
  double directPerRound_, directSecondsPerSpp_;
  double drainIterations_ = 0, positionsPerIteration_ = 1;
  double perPosition_ = 0, lastElapsed_ = 0;
  size_t lastTaken_ = 0;
};
}  // namespace

RgbImage renderPmcForTime(const Scene& scene, const RenderSettings& s, const PmcTimeParts& parts, RenderStats& stats) {
  const PmcSettings& p = pmcOf(s);
  const size_t pixels = size_t(s.width) * size_t(s.height);
  // The direct pass keeps its ratio to the pool (--direct-samples per --spp): one sample per
  // pixel first, to measure its cost, the rest when the population has ended.
  const int directSamples = erptOf(s).directSamples;
  const double directPerRound = directSamples > 0 ? double(directSamples) / double(s.spp) : 0.0;
  RgbImage directFirst;
  double directSecondsPerSpp = 0;
  if (directPerRound > 0) {
    RenderSettings one = s;
    erptOf(one).directSamples = 1;
    const Clock::time_point t = Clock::now();
    directFirst = renderDirectPass(scene, one, stats);
    directSecondsPerSpp = secondsSince(t);
  }

  PmcPopulation population(parts.setup,
                           PmcPopulation::Config{parts.ctx, chainSettingsOf(erptOf(s)), p, s.seed, &parts.setup.film},
                           parts.mixture, stats);
  const StratifiedPool pool{uint32_t(pixels), kOpenEndedRounds, streamKey(s.seed, kPoolStream, 0)};
  RoundBudget budget(s, p, pixels, parts.start, directPerRound, directSecondsPerSpp);
  auto progress = [&](double) {
    if (s.progress) s.progress(std::min(1.0, secondsSince(parts.start) / s.timeBudget));
  };
  // Not stoppable from outside: an interrupt ends the rounds after the one in progress
  // (RoundBudget) and the population drains, so the image is always a complete one.
  population.run(PoolRounds::all(pool), -1, progress, nullptr, std::function<size_t(size_t)>(std::ref(budget)));
  const double rounds = double(population.positionsTaken()) / double(pixels);

  RgbImage direct;
  if (directPerRound > 0) {
    const int total = std::max(1, int(std::lround(directPerRound * rounds)));
    direct = directFirst;
    if (total > 1) {
      RenderSettings rest = s;
      rest.seed = streamKey(s.seed, kDirectRestStream, 0);
      erptOf(rest).directSamples = total - 1;
      const RgbImage more = renderDirectPass(scene, rest, stats);
      for (size_t i = 0; i < direct.pixels.size(); ++i)
        direct.pixels[i] = (direct.pixels[i] + more.pixels[i] * float(total - 1)) / float(total);
    }
  }
  stats.spp = int(std::lround(rounds));  // whole rounds
  stats.partial = false;
  stats.extraImages.emplace_back("strategy", population.strategyImage());
  return redistributionImage(s, parts.setup.film.resolve(rounds), direct,
                             erptOf(s).pmFilterRadius >= 0 ? &population.proposalTally() : nullptr, &stats.extraImages);
}

}  // namespace erpt
