// A chain lane: one chain queue stepped by one thread from proposal to deposit, with no
// synchronisation with the other lanes, depositing into an ExactFilm they share (sums that do
// not depend on the order of the adds, so the image is the same for any thread count). The
// unit every chain machine runs its chains in: ERPT's and MLT's seed-fed lanes (chain_lanes.h)
// and PMC-ER's population, whose members live in a fixed set of lanes (pmc_population.h).
#pragma once

#include <cmath>
#include <vector>

#include "models/exact_film.h"
#include "stages/chain_step.h"
#include "stages/chain_stages.h"
#include "tracer/tracer.h"

namespace erpt {

// The unit of an ExactFilm whose deposits are about `depositEnergy` each: 2^-24 of it (a
// deposit's rounding error below a float's precision of the deposit; exact_film.h). Without a
// deposit energy, a fixed 2^-40; what is too large for it goes the large-deposit way.
inline double exactFilmUnit(double depositEnergy) {
  return depositEnergy > 0 && std::isfinite(depositEnergy) ? std::ldexp(depositEnergy, -24) : std::ldexp(1.0, -40);
}

struct ChainLane {
  explicit ChainLane(size_t slots) : q(slots) {}
  StepQueues q;
  // What this lane's thread accumulates until its owner collects it (takeTotals).
  StageTimes times;
  DepositFilters filters;  // this lane's filter counts (a proposal tally is shared)
  std::vector<LargeDeposit> large;
  double deposited = 0;
  uint64_t rays = 0;

  // One step of every chain in the queue (the stages over the whole queue as one range, on the
  // calling thread), then its deposit records into `film` (or, too large for it, `large`).
  // `film` null: the deposits are dropped (a training population).
  void step(const Tracer& tracer, const StepConfig& ctx, const ProposalPolicy* policy, StepCounters& counters,
            ExactFilm* film);

  struct Totals {
    uint64_t rays = 0;
    double deposited = 0;
    uint64_t discarded = 0;
    double discardedEnergy = 0;
  };
  // Moves the lane's counts into `totals`, its stage times (scaled by `timeScale`) into `times`
  // and its large deposits into `large`, and starts them again from zero.
  void takeTotals(Totals& totals, StageTimes& stageTimes, double timeScale, std::vector<LargeDeposit>& largeDeposits);
};

}  // namespace erpt
