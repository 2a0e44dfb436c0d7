// The loop the caustic perturbations' startRange runs: over the slots of a range whose
// proposal chose this unit, read the chain's path, call the unit's start for one proposal
// (inlined: a template argument, not a pointer), and write the proposal's columns and first
// ray. One loop per unit keeps the per-proposal math inline and the dispatch on the kind in
// the mutate stage's loop over units. (Lens starts read no vertices and make their eye rays
// in batches: lens.cpp.)
#pragma once

#include "core/rng.h"
#include "mutations/mutation.h"

namespace erpt {

// StartOne is a function (a template argument, so the call is direct and can be inlined; a
// function-pointer argument stays an indirect call per proposal).
template <auto StartOne>
void startEach(MutationKind kind, const StepConfig& ctx, const ChainQueue& chains, const VertexQueue& chainVertices,
               ProposalQueue& proposals, RayQueue& rays, IndexRange range) {
  uint8_t kinds[kMaxChainVertices];
  PathVertex y[kMaxChainVertices];
  for (size_t i = range.begin; i < range.end; ++i) {
    if (proposals.mutation[i] != uint8_t(kind) || proposals.state[i] != kProposalWalking) continue;
    const int n = chains.vertexCount[i];
    unpackSignature(chains.signature[i], n, kinds);
    loadChainPath(chains, chainVertices, i, y);
    const float filmX = chains.filmX[i], filmY = chains.filmY[i], size = proposals.perturbSize[i];
    const uint64_t key = chains.key[i];
    const uint32_t step = chains.step[i];
    ProposalStart start;
    start.filmX = filmX;
    start.filmY = filmY;
    StartOne(ctx.measure, CurrentPath{y, kinds, n, filmX, filmY}, filmX, filmY, size,
             uniformFloat(key, stepDim(step, kDimStart1)), uniformFloat(key, stepDim(step, kDimStart2)), start);
    proposals.filmX[i] = start.filmX;
    proposals.filmY[i] = start.filmY;
    if (start.reject != kRejectNone) {
      rejectProposal(proposals, rays, i, start.reject);
      continue;
    }
    proposals.cursor[i] = int8_t(start.cursor);
    proposals.walk[i] = int8_t(start.walk);
    proposals.regenFirst[i] = int8_t(start.regenFirst);
    proposals.regenLast[i] = int8_t(start.regenLast);
    proposals.connectTo[i] = int8_t(start.connectTo);
    setRay(rays, i, start.origin, start.direction, start.tnear, start.tfar);
  }
}

}  // namespace erpt
