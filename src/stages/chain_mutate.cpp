// Mutate stage: picks the mutation for each chain (a ProposalPolicy) and emits the
// proposal's first ray (the chosen units' starts).
#include <algorithm>

#include "stages/chain_stages.h"
#include "core/rng.h"
#include "models/surface.h"
#include "tracer/tracer.h"

namespace erpt {

namespace {

// ERPT's choice: the strategy picks the family from the path's signature (so it is the same
// at y and z: ratio 1), the settings pick the unit and the size.
class ErptChooser final : public ProposalPolicy {
 public:
  void choose(const StepConfig& ctx, const ChainQueue& chains, ProposalQueue& proposals, RayQueue& rays,
              IndexRange range) const override {
    uint8_t kinds[kMaxChainVertices];
    const double bidirectional = ctx.settings.bidirectional;
    for (size_t i = range.begin; i < range.end; ++i) {
      if (chains.stepsLeft[i] == 0) continue;
      // The bidirectional mutation's coin, the same for every path (it cancels in the
      // acceptance ratio); its walks run after the mutate stage (chain_bidirectional.cpp).
      if (bidirectional > 0 && uniformDouble(chains.key[i], stepDim(chains.step[i], kDimBidirectional)) < bidirectional) {
        proposals.mutation[i] = uint8_t(MutationKind::Bidirectional);
        proposals.state[i] = kProposalBidirectional;
        disableRay(rays, i);
        continue;
      }
      const int n = chains.vertexCount[i];
      unpackSignature(chains.signature[i], n, kinds);
      if (choosesManifold(ctx, chains, i, kinds, n)) {
        proposals.mutation[i] = uint8_t(MutationKind::Manifold);
        proposals.perturbSize[i] = ctx.settings.lensRadius;
        proposals.state[i] = kProposalWalking;
        continue;
      }
      const MutationKind family = chooseMutation(ctx.settings.strategy, kinds, n,
                                                 uniformFloat(chains.key[i], stepDim(chains.step[i], kDimStrategy)));
      if (family == MutationKind::None) {
        rejectProposal(proposals, rays, i, kRejectNoMutation);
        continue;
      }
      proposals.mutation[i] = uint8_t(family == MutationKind::Lens ? ctx.lensKind() : ctx.causticKind());
      proposals.perturbSize[i] = ctx.settings.lensRadius;
      proposals.state[i] = kProposalWalking;
    }
  }
};

}  // namespace

const ProposalPolicy& erptChooser() {
  static const ErptChooser chooser;
  return chooser;
}

bool resetProposal(const ChainQueue& chains, ProposalQueue& proposals, RayQueue& rays, size_t i) {
  proposals.mutation[i] = uint8_t(MutationKind::None);
  proposals.reason[i] = kRejectNone;
  proposals.connectTo[i] = -1;
  proposals.regenFirst[i] = 1;
  proposals.regenLast[i] = 0;
  proposals.acceptance[i] = 0;
  proposals.component[i] = 0;
  proposals.selection[i] = 1;
  proposals.measureRatio[i] = 1;
  proposals.state[i] = kProposalRejected;  // until the chooser picks a mutation
  if (chains.stepsLeft[i] > 0) return true;
  rejectProposal(proposals, rays, i, kRejectNone);
  return false;
}

void stageChainMutate(const StepConfig& ctx, const ChainQueue& chains, const VertexQueue& chainVertices,
                     ProposalQueue& proposals, RayQueue& rays, IndexRange range, const ProposalPolicy* policy) {
  // Pass 1: every slot's mutation unit and perturbation size.
  for (size_t i = range.begin; i < range.end; ++i) resetProposal(chains, proposals, rays, i);
  (policy ? *policy : erptChooser()).choose(ctx, chains, proposals, rays, range);
  // Pass 2, the one dispatch on the kind: each unit starts its own proposals (those waiting
  // in state kProposalLarge are started by the policy's startOwnProposals).
  bool used[kMutationKindCount] = {};
  for (size_t i = range.begin; i < range.end; ++i)
    if (proposals.state[i] == kProposalWalking) used[proposals.mutation[i]] = true;
  for (int k = 1; k < kMutationKindCount; ++k)
    if (used[k]) mutationOf(MutationKind(k)).startRange(ctx, chains, chainVertices, proposals, rays, range);
}

}  // namespace erpt
