#include "integrators/chain_lane.h"

#include <chrono>

namespace erpt {

void ChainLane::step(const Tracer& tracer, const StepConfig& ctx, const ProposalPolicy* policy, StepCounters& counters,
                     ExactFilm* film) {
  const ChainStep chainStep{tracer, ctx, &times, q.chains.size(), policy};
  rays += chainStep.run(q, counters);
  if (!film) return;
  const auto start = std::chrono::steady_clock::now();
  ConcurrentDeposits target{*film, large};
  deposited += applyDeposits(q.chains, q.proposals, q.deposits, IndexRange{0, q.chains.size()}, ctx.measure.film, target,
                             filters);
  times.add("chain deposit", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

void ChainLane::takeTotals(Totals& totals, StageTimes& stageTimes, double timeScale,
                           std::vector<LargeDeposit>& largeDeposits) {
  totals.rays += rays;
  totals.deposited += deposited;
  totals.discarded += filters.discarded;
  totals.discardedEnergy += filters.discardedEnergy;
  rays = 0, deposited = 0, filters.discarded = 0, filters.discardedEnergy = 0;
  for (const auto& [name, seconds] : times.all()) stageTimes.add(name, seconds * timeScale);
  times = StageTimes{};
  largeDeposits.insert(largeDeposits.end(), large.begin(), large.end());
  large.clear();
}

}  // namespace erpt
