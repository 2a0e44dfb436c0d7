// ERPT statistics after a render: what the chains did and where the time went.
#include <cstdio>
#include <string>

#include "integrator_stats.h"
#include "kernels/erpt_path.h"

namespace erpt {

void addErptStats(ErptStats& to, const ErptStats& from) {
  to.seeds += from.seeds;
  to.chains += from.chains;
  to.mutations += from.mutations;
  for (int k = 0; k < kMutationKindCount; ++k) to.proposed[k] += from.proposed[k], to.accepted[k] += from.accepted[k];
  for (size_t r = 0; r < std::size(to.rejected); ++r) to.rejected[r] += from.rejected[r];
  to.deposits += from.deposits;
  for (int r = 0; r < kInPlaceReasonCount; ++r) to.inPlace[r] += from.inPlace[r];
  to.cappedSeeds += from.cappedSeeds;
  to.rays += from.rays;
  to.pilotEnergy = from.pilotEnergy;
  to.depositEnergy = from.depositEnergy;
  to.erptSeconds += from.erptSeconds;
  to.discardedDeposits += from.discardedDeposits;
  to.discardedEnergy += from.discardedEnergy;
}

void printChainMoves(const char* prefix, const ErptStats& e) {
  auto pct = [](uint64_t a, uint64_t b) { return b ? 100.0 * double(a) / double(b) : 0.0; };
  std::fprintf(stderr, "%s:", prefix);
  for (int k = 1; k < kMutationKindCount; ++k)
    if (e.proposed[k] > 0)
      std::fprintf(stderr, " %s %llu proposed, %.1f%% accepted;", mutationName(MutationKind(k)),
                   (unsigned long long)e.proposed[k], pct(e.accepted[k], e.proposed[k]));
  std::fprintf(stderr, " no mutation %llu\n", (unsigned long long)e.proposed[size_t(MutationKind::None)]);
}

void printRejections(const char* prefix, const ErptStats& e) {
  std::fprintf(stderr, "%s: rejected:", prefix);
  for (int r = kRejectNoMutation; r < kRejectReasonCount; ++r)
    std::fprintf(stderr, "%s %s %llu", r == kRejectNoMutation ? "" : ",", rejectReasonName(RejectReason(r)),
                 (unsigned long long)e.rejected[r]);
  std::fprintf(stderr, "\n");
}

void printChainStageSeconds(const RenderStats& stats) {
  std::fprintf(stderr, "stage seconds:");
  const std::string prefix = "chain ";  // the chain engine's stages (chain_step.cpp, chain_lanes.cpp)
  for (const auto& [name, seconds] : stats.stages.all())
    if (name.rfind(prefix, 0) == 0) std::fprintf(stderr, " %s %.2f", name.c_str() + prefix.size(), seconds);
  std::fprintf(stderr, "\n");
}

void printErptSummary(const RenderStats& stats) {
  const ErptStats& e = erptStatsOf(stats);
  auto pct = [](uint64_t a, uint64_t b) { return b ? 100.0 * double(a) / double(b) : 0.0; };
  uint64_t inPlace = 0;
  for (uint64_t n : e.inPlace) inPlace += n;
  std::fprintf(stderr,
               "erpt: e_ave %.4g, e_d %.4g; %llu seeds, %llu chains, %llu mutations (%.2f M/s in %.2f s of chain "
               "loop), %llu deposits\n",
               e.pilotEnergy, e.depositEnergy, (unsigned long long)e.seeds, (unsigned long long)e.chains,
               (unsigned long long)e.mutations, e.erptSeconds > 0 ? double(e.mutations) / e.erptSeconds * 1e-6 : 0.0,
               e.erptSeconds, (unsigned long long)e.deposits);
  std::fprintf(stderr, "erpt: seeds deposited in place %llu:", (unsigned long long)inPlace);
  for (int r = 0; r < kInPlaceReasonCount; ++r)
    std::fprintf(stderr, "%s %s %llu", r == 0 ? "" : ",", inPlaceReasonName(InPlaceReason(r)),
                 (unsigned long long)e.inPlace[r]);
  std::fprintf(stderr, "; seeds with capped chain counts %llu\n", (unsigned long long)e.cappedSeeds);
  printChainMoves("erpt", e);
  if (e.discardedDeposits > 0)
    std::fprintf(stderr, "erpt: consecutive-sample filter threw away %llu deposits (%.3g%% of the deposited energy)\n",
                 (unsigned long long)e.discardedDeposits,
                 pct(uint64_t(e.discardedEnergy * 1e6), uint64_t((e.discardedEnergy + double(e.deposits) * e.depositEnergy) * 1e6)));
  printRejections("erpt", e);
  std::fprintf(stderr, "erpt: %.2f Mrays/s in the chain loop; ", e.erptSeconds > 0 ? double(e.rays) / e.erptSeconds * 1e-6 : 0.0);
  printChainStageSeconds(stats);
}

}  // namespace erpt
