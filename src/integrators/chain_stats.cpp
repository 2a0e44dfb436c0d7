// The chain integrators' shared statistics (ChainStats): how a time-budgeted render adds them
// over its passes, and the summary lines ERPT, PMC-ER and MLT print about their chain steps.
#include <cstdio>
#include <iterator>
#include <string>

#include "integrator_stats.h"
#include "kernels/erpt_path.h"

namespace erpt {

void addChainStats(ChainStats& to, const ChainStats& from) {
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
  to.chainSeconds += from.chainSeconds;
  to.discardedDeposits += from.discardedDeposits;
  to.discardedEnergy += from.discardedEnergy;
}

void printChainMoves(const char* prefix, const ChainStats& e) {
  auto pct = [](uint64_t a, uint64_t b) { return b ? 100.0 * double(a) / double(b) : 0.0; };
  std::fprintf(stderr, "%s:", prefix);
  for (int k = 1; k < kMutationKindCount; ++k)
    if (e.proposed[k] > 0)
      std::fprintf(stderr, " %s %llu proposed, %.1f%% accepted;", mutationName(MutationKind(k)),
                   (unsigned long long)e.proposed[k], pct(e.accepted[k], e.proposed[k]));
  std::fprintf(stderr, " no mutation %llu\n", (unsigned long long)e.proposed[size_t(MutationKind::None)]);
}

void printInPlaceReasons(const char* prefix, const ChainStats& e) {
  uint64_t total = 0;
  for (uint64_t n : e.inPlace) total += n;
  std::fprintf(stderr, "%s: seeds deposited in place %llu", prefix, (unsigned long long)total);
  const char* separator = ":";  // the reasons that occurred
  for (int r = 0; r < kInPlaceReasonCount; ++r)
    if (e.inPlace[r] > 0) {
      std::fprintf(stderr, "%s %s %llu", separator, inPlaceReasonName(InPlaceReason(r)), (unsigned long long)e.inPlace[r]);
      separator = ",";
    }
}

void printRejections(const char* prefix, const ChainStats& e) {
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

}  // namespace erpt
