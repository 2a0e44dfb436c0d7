// MLT statistics after a render: the bootstrap, the chains, acceptance per mutation kind.
#include <cstdio>

#include "integrator_stats.h"
#include "kernels/erpt_path.h"

namespace erpt {

void addMltStats(MltStats& to, const MltStats& from) {
  to.b = from.b;  // each pass estimates b on its own; the last one is shown
  to.inPlaceEnergy = from.inPlaceEnergy;
  to.bootstrapSamples += from.bootstrapSamples;
  to.domainSeeds += from.domainSeeds;
  to.inPlaceSeeds += from.inPlaceSeeds;
  to.chains += from.chains;
  to.chainLength = from.chainLength;
  to.energyPerStep = from.energyPerStep;
  to.chainSeconds += from.chainSeconds;
  to.bootstrapSeconds += from.bootstrapSeconds;
}

void printMltSummary(const RenderStats& stats) {
  const MltStats& m = mltStatsOf(stats);
  const ChainStats& e = chainStatsOf(stats);
  std::fprintf(stderr,
               "mlt: b %.6g (bootstrap: %llu samples, %llu paths for the chains, %llu deposited in place holding "
               "%.4g), %.2f s\n",
               m.b, (unsigned long long)m.bootstrapSamples, (unsigned long long)m.domainSeeds,
               (unsigned long long)m.inPlaceSeeds, m.inPlaceEnergy, m.bootstrapSeconds);
  std::fprintf(stderr, "mlt: %llu chains x %llu steps, %llu mutations (%.2f M/s in %.2f s), %.4g per step; %llu rays in the chains\n",
               (unsigned long long)m.chains, (unsigned long long)m.chainLength, (unsigned long long)e.mutations,
               m.chainSeconds > 0 ? double(e.mutations) / m.chainSeconds * 1e-6 : 0.0, m.chainSeconds, m.energyPerStep,
               (unsigned long long)e.rays);
  printInPlaceReasons("mlt", e);
  std::fprintf(stderr, "\n");
  printChainMoves("mlt", e);
  printRejections("mlt", e);
  std::fprintf(stderr, "mlt: ");
  printChainStageSeconds(stats);
}

}  // namespace erpt
