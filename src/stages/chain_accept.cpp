// Accept stage: each complete proposal's unit gives its acceptance probability (mutation.h),
// then the Metropolis coin, the step's deposit records (the rule lives in chain_deposit.cpp),
// and, on acceptance, the unit moves the chain. No branch on the kind of proposal: the lens
// contribution packet takes the proposals of its shape by itself, 64 slots ahead, and hands
// their f(z) to the unit's verdict.
#include <algorithm>
#include <cmath>

#include "core/rng.h"
#include "mutations/lens_contribution_packet.h"
#include "stages/chain_stages.h"

namespace erpt {

void stageChainAccept(const StepConfig& ctx, ChainQueue& chains, VertexQueue& chainVertices,
                     ProposalQueue& proposals, const VertexQueue& proposalVertices, DepositQueue& deposits,
                     StepCounters& counters, IndexRange range) {
  PathVertex y[kMaxChainVertices], z[kMaxChainVertices];
  uint64_t proposed[kMutationKindCount] = {}, accepted[kMutationKindCount] = {}, rejected[kRejectReasonCount] = {};
  const bool moves = ctx.settings.flow != FlowRule::DetailedBalance;  // detailed balance: x never moves
  LensContributionPacket lens;
  for (size_t i = range.begin; i < range.end; ++i) {
    if ((i - range.begin) % LensContributionPacket::kCapacity == 0)
      lens.evaluate(ctx, chains, chainVertices, proposals, proposalVertices, i,
                    std::min(LensContributionPacket::kCapacity, range.end - i));
    clearStepDeposits(deposits, i);
    if (chains.stepsLeft[i] == 0) continue;
    const MutationKind kind = MutationKind(proposals.mutation[i]);
    const AcceptSlot slot{chains, chainVertices, proposals, proposalVertices, i, y, z};
    // Only a proposal that chose a unit completes; its unit judges it, from f(z) in the lens
    // packet when the packet took it.
    const Acceptance a = proposals.state[i] != kProposalComplete ? Acceptance{}
                         : lens.took(i)                          ? perturbationAcceptanceOf(ctx, slot, lens.fz(i))
                                                                 : mutationOf(kind).acceptance(ctx, slot);
    proposals.acceptance[i] = a.q;
    // 53 bits: with a 24-bit coin every q below 2^-24 would be accepted with probability 2^-24.
    const bool accept = uniformDouble(chains.key[i], stepDim(chains.step[i], kDimAccept)) < a.q;
    if (a.q > 0 && !accept) proposals.reason[i] = kRejectByChance;
    ++proposed[size_t(kind)];
    if (accept)
      ++accepted[size_t(kind)];
    else
      ++rejected[proposals.reason[i]];

    const StepDeposit before{chains.filmX[i], chains.filmY[i], chains.colorAt(i)};
    const StepDeposit proposal{proposals.filmX[i], proposals.filmY[i], a.fz};
    if (accept && moves) {
      mutationOf(kind).moveChain(slot, a);
      chains.filmX[i] = proposals.filmX[i];
      chains.filmY[i] = proposals.filmY[i];
      chains.colorSet(i, a.fz);
    }
    writeStepDeposits(ctx.settings, before, proposal, a.q, accept && moves, chains.energy[i], deposits, i);
    ++chains.step[i];
    --chains.stepsLeft[i];
  }
  for (int k = 0; k < kMutationKindCount; ++k) {
    counters.proposed[k] += proposed[k];
    counters.accepted[k] += accepted[k];
  }
  for (int r = 0; r < kRejectReasonCount; ++r) counters.rejected[r] += rejected[r];
}

}  // namespace erpt
