// PMC-ER statistics after a render: the population, the pool, acceptance per radius and
// kind, the mixture weights, the energy the resampling moved, and where the time went.
#include <cstdio>

#include "integrator_stats.h"

namespace erpt {

void addPmcStats(PmcStats& to, const PmcStats& from) {
  to.iterations += from.iterations;
  to.drainIterations += from.drainIterations;
  to.trainingIterations += from.trainingIterations;
  to.population = from.population;
  to.requestedPopulation = from.requestedPopulation;
  to.poolSize += from.poolSize;
  to.poolEnergy += from.poolEnergy;
  to.poolUsed += from.poolUsed;
  to.candidates += from.candidates;
  to.inPlaceSeeds += from.inPlaceSeeds;
  to.membersBorn += from.membersBorn;
  to.eliminated += from.eliminated;
  to.split += from.split;
  to.energyRegenerated += from.energyRegenerated;
  to.energyEliminated += from.energyEliminated;
  to.energyFinal += from.energyFinal;
  to.steps += from.steps;
  to.depositEnergy = from.depositEnergy;
  to.meanDeposit = from.meanDeposit;
  to.radiusCount = from.radiusCount;
  for (int k = 0; k < kMaxPmcRadii; ++k) {
    to.radii[k] = from.radii[k];
    for (int m = 0; m < kMutationKindCount; ++m) {
      to.proposed[k][m] += from.proposed[k][m];
      to.accepted[k][m] += from.accepted[k][m];
      to.acceptanceSum[k][m] += from.acceptanceSum[k][m];
    }
    for (int b = 0; b < kAlphaBins; ++b) to.alphaHistogram[k][b] += from.alphaHistogram[k][b];
  }
  to.resampleSeconds += from.resampleSeconds;
  to.regenerateSeconds += from.regenerateSeconds;
  to.chainSeconds += from.chainSeconds;
  to.trainSeconds += from.trainSeconds;
}

void printPmcSummary(const RenderStats& stats) {
  const PmcStats& p = pmcStatsOf(stats);
  const ChainStats& e = chainStatsOf(stats);
  std::fprintf(stderr,
               "pmc-er: %llu iterations (%llu draining) + %llu training, population %llu; pool %llu of %llu "
               "positions, %llu candidates, %llu seeds in place\n",
               (unsigned long long)p.iterations, (unsigned long long)p.drainIterations,
               (unsigned long long)p.trainingIterations, (unsigned long long)p.population,
               (unsigned long long)p.poolUsed, (unsigned long long)p.poolSize, (unsigned long long)p.candidates,
               (unsigned long long)p.inPlaceSeeds);
  printInPlaceReasons("pmc-er", e);
  std::fprintf(stderr, "\n");
  if (p.requestedPopulation > p.population)
    std::fprintf(stderr, "pmc-er: note: --population %llu is more than the pool's %llu positions (pixels x spp); %llu members ran\n",
                 (unsigned long long)p.requestedPopulation, (unsigned long long)p.population, (unsigned long long)p.population);
  std::fprintf(stderr,
               "pmc-er: e_ave %.4g, e_d (eq. 4) %.4g, mean deposit per step %.4g; resampling: %llu members born, "
               "%llu eliminated, %llu copies; energy regenerated %.4g, eliminated %.4g, left at the end %.4g\n",
               e.pilotEnergy, p.depositEnergy, p.meanDeposit, (unsigned long long)p.membersBorn,
               (unsigned long long)p.eliminated, (unsigned long long)p.split, p.energyRegenerated, p.energyEliminated,
               p.energyFinal);
  for (int k = 0; k < p.radiusCount; ++k) {
    std::fprintf(stderr, "pmc-er: radius %g:", p.radii[k]);
    for (int m = 1; m < kMutationKindCount; ++m)
      if (p.proposed[k][m] > 0)
        std::fprintf(stderr, " %s %llu proposed, %.1f%% accepted (mean q %.3f);", mutationName(MutationKind(m)),
                     (unsigned long long)p.proposed[k][m], 100.0 * double(p.accepted[k][m]) / double(p.proposed[k][m]),
                     p.acceptanceSum[k][m] / double(p.proposed[k][m]));
    std::fprintf(stderr, " alpha histogram (0..1 in %d bins):", kAlphaBins);
    for (int b = 0; b < kAlphaBins; ++b) std::fprintf(stderr, " %llu", (unsigned long long)p.alphaHistogram[k][b]);
    std::fprintf(stderr, "\n");
  }
  const double mutations = double(e.mutations);
  std::fprintf(stderr,
               "pmc-er: %.2f M mutations/s in the chain loop (%.2f s), resampling %.2f s, regeneration (pool path "
               "tracing) %.2f s, training %.2f s\n",
               p.chainSeconds > 0 ? mutations / p.chainSeconds * 1e-6 : 0.0, p.chainSeconds, p.resampleSeconds,
               p.regenerateSeconds, p.trainSeconds);
}

}  // namespace erpt
