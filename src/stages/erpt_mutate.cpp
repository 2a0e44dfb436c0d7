// ERPT mutate stage: picks the mutation for each chain and emits the proposal's first ray.
#include <algorithm>

#include "erpt/erpt_stages.h"
#include "erpt/rng.h"
#include "erpt/surface.h"
#include "erpt/tracer.h"

namespace erpt {

void stageErptMutate(const ErptStepContext& ctx, const ChainQueue& chains, const VertexQueue& chainVertices,
                     ProposalQueue& proposals, RayQueue& rays, IndexRange range) {
  // Pass 1: every slot's mutation (the strategy picks the family from the path's signature,
  // the settings pick the unit) and perturbation size.
  uint8_t kinds[kMaxChainVertices];
  bool used[kMutationKindCount] = {};
  for (size_t i = range.begin; i < range.end; ++i) {
    proposals.mutation[i] = uint8_t(MutationKind::None);
    proposals.reason[i] = kRejectNone;
    proposals.connectTo[i] = -1;
    proposals.regenFirst[i] = 1;
    proposals.regenLast[i] = 0;
    proposals.acceptance[i] = 0;
    if (chains.stepsLeft[i] == 0) {
      rejectProposal(proposals, rays, i, kRejectNone);
      continue;
    }
    const int n = chains.vertexCount[i];
    unpackSignature(chains.signature[i], n, kinds);
    const MutationKind family = chooseMutation(ctx.settings.strategy, kinds, n,
                                               uniformFloat(chains.key[i], stepDim(chains.step[i], kDimStrategy)));
    if (family == MutationKind::None) {
      rejectProposal(proposals, rays, i, kRejectNoMutation);
      continue;
    }
    const MutationKind kind = family == MutationKind::Lens ? ctx.lensKind() : ctx.causticKind();
    proposals.mutation[i] = uint8_t(kind);
    proposals.perturbSize[i] = ctx.settings.lensRadius;
    proposals.state[i] = kProposalWalking;
    used[size_t(kind)] = true;
  }
  // Pass 2, the one dispatch on the kind: each unit starts its own proposals.
  for (int k = 1; k < kMutationKindCount; ++k)
    if (used[k]) mutationOf(MutationKind(k)).startRange(ctx, chains, chainVertices, proposals, rays, range);
}

}  // namespace erpt
