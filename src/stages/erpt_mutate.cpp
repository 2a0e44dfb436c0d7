// ERPT mutate stage: picks the mutation for each chain and emits the proposal's first ray.
#include <algorithm>

#include "erpt/erpt_stages.h"
#include "erpt/rng.h"
#include "erpt/surface.h"
#include "erpt/tracer.h"

namespace erpt {

namespace {

void reject(ProposalQueue& p, RayQueue& rays, size_t i, RejectReason why) {
  p.state[i] = kProposalRejected;
  p.reason[i] = why;
  disableRay(rays, i);
}

}  // namespace

void stageErptMutate(const ErptStepContext& ctx, const ChainQueue& chains, const VertexQueue& chainVertices,
                     ProposalQueue& proposals, RayQueue& rays, IndexRange range) {
  const MeasureContext& mc = ctx.measure;
  uint8_t kinds[kMaxChainVertices];
  PathVertex y[kMaxChainVertices];
  for (size_t i = range.begin; i < range.end; ++i) {
    proposals.mutation[i] = uint8_t(MutationKind::None);
    proposals.reason[i] = kRejectNone;
    proposals.connectTo[i] = -1;
    proposals.regenFirst[i] = 1;
    proposals.regenLast[i] = 0;
    proposals.acceptance[i] = 0;
    if (chains.stepsLeft[i] == 0) {
      reject(proposals, rays, i, kRejectNone);
      continue;
    }
    const int n = chains.vertexCount[i];
    unpackSignature(chains.signature[i], n, kinds);
    const uint64_t key = chains.key[i];
    const uint32_t step = chains.step[i];
    // The strategy picks the family, the settings the unit; the one dispatch on the kind.
    const MutationKind family =
        chooseMutation(ctx.settings.strategy, kinds, n, uniformFloat(key, stepDim(step, kDimStrategy)));
    if (family == MutationKind::None) {
      reject(proposals, rays, i, kRejectNoMutation);
      continue;
    }
    const MutationKind kind = family == MutationKind::Lens ? ctx.lensKind() : ctx.causticKind();
    const Mutation& unit = mutationOf(kind);
    const float size = ctx.settings.lensRadius;
    proposals.mutation[i] = uint8_t(kind);
    proposals.perturbSize[i] = size;
    proposals.state[i] = kProposalWalking;
    // Lens starts read the film position and signature only; caustic starts read the vertices
    // from the eye to the source (loading a whole path per slot is what this stage costs most).
    if (family == MutationKind::Caustic) loadChainPath(chains, chainVertices, i, y);
    const float filmX = chains.filmX[i], filmY = chains.filmY[i];
    const CurrentPath current{y, kinds, n, filmX, filmY};
    ProposalStart start;
    start.filmX = filmX;
    start.filmY = filmY;
    unit.start(mc, current, filmX, filmY, size, uniformFloat(key, stepDim(step, kDimStart1)),
               uniformFloat(key, stepDim(step, kDimStart2)), start);
    proposals.filmX[i] = start.filmX;
    proposals.filmY[i] = start.filmY;
    if (start.reject != kRejectNone) {
      reject(proposals, rays, i, start.reject);
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
