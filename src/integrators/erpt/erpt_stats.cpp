// ERPT's summary after a render: its energies, what its chains did and where the time went.
#include <cstdio>
#include <string>

#include "integrator_stats.h"
#include "kernels/erpt_path.h"

namespace erpt {

void printErptSummary(const RenderStats& stats) {
  const ChainStats& e = chainStatsOf(stats);
  auto pct = [](uint64_t a, uint64_t b) { return b ? 100.0 * double(a) / double(b) : 0.0; };
  std::fprintf(stderr,
               "erpt: e_ave %.4g, e_d %.4g; %llu seeds, %llu chains, %llu mutations (%.2f M/s in %.2f s of chain "
               "loop), %llu deposits\n",
               e.pilotEnergy, e.depositEnergy, (unsigned long long)e.seeds, (unsigned long long)e.chains,
               (unsigned long long)e.mutations, e.chainSeconds > 0 ? double(e.mutations) / e.chainSeconds * 1e-6 : 0.0,
               e.chainSeconds, (unsigned long long)e.deposits);
  printInPlaceReasons("erpt", e);
  std::fprintf(stderr, "; seeds with capped chain counts %llu\n", (unsigned long long)e.cappedSeeds);
  printChainMoves("erpt", e);
  if (e.discardedDeposits > 0)
    std::fprintf(stderr, "erpt: consecutive-sample filter threw away %llu deposits (%.3g%% of the deposited energy)\n",
                 (unsigned long long)e.discardedDeposits,
                 pct(uint64_t(e.discardedEnergy * 1e6), uint64_t((e.discardedEnergy + double(e.deposits) * e.depositEnergy) * 1e6)));
  printRejections("erpt", e);
  std::fprintf(stderr, "erpt: %.2f Mrays/s in the chain loop; ", e.chainSeconds > 0 ? double(e.rays) / e.chainSeconds * 1e-6 : 0.0);
  printChainStageSeconds(stats);
}

}  // namespace erpt
