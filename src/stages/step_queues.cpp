// The chain queues of ERPT: allocation, a chain's path as values, a chain started at a seed.
#include <algorithm>
#include <cmath>

#include "stages/chain_stages.h"
#include "tracer/tracer.h"

namespace erpt {

StepQueues::StepQueues(size_t capacity) {
  chains.resize(capacity);
  proposals.resize(capacity);
  chainVertices.resize(capacity * kMaxChainVertices);
  proposalVertices.resize(capacity * kMaxChainVertices);
  prepareRays(rays, capacity);
  prepareRays(shadowRays, capacity);
  hits.resize(capacity);
  prepareRays(denseRays, capacity);
  denseHits.resize(capacity);
  denseSlots.reserve(capacity);
  deposits.resize(capacity * kDepositsPerStep);
  for (size_t i = 0; i < capacity; ++i) chains.stepsLeft[i] = 0;
}

size_t StepQueues::bytesPerSlot() {
  return sizeof(ChainQueue::Row) + sizeof(ProposalQueue::Row) + 2 * kMaxChainVertices * sizeof(VertexQueue::Row) +
         3 * sizeof(RayQueue::Row) + 2 * sizeof(HitQueue::Row) + sizeof(uint32_t) + kDepositsPerStep * sizeof(DepositQueue::Row);
}

bool pathHasZeroContribution(const StepConfig& ctx, const PathVertex* path, int n, float filmX, float filmY) {
  uint8_t kinds[kMaxChainVertices];
  for (int j = 0; j < n; ++j) kinds[j] = path[j].kind;
  // Every mutation the strategy may pick for this signature (the choice depends on the
  // signature only, which mutations preserve) must see a path of positive, finite f.
  for (float u : {0.0f, 0.999f}) {
    const MutationKind family = chooseMutation(ctx.settings.strategy, kinds, n, u);
    if (family == MutationKind::None) continue;
    const MutationKind kind = family == MutationKind::Lens ? ctx.lensKind() : ctx.causticKind();
    const float f = luminance(contributionFor(kind, ctx.measure, path, n, filmX, filmY));
    if (!(f > 0) || !std::isfinite(f)) return true;
  }
  if (ctx.settings.manifold > 0 && manifoldChainEnd(kinds, n) > 0) {
    const float f = luminance(manifoldContribution(ctx.measure, path, n, filmX, filmY));
    if (!(f > 0) || !std::isfinite(f)) return true;
  }
  return false;
}

void loadChainFromSeed(ChainQueue& chains, VertexQueue& chainVertices, size_t slot, const SeedStore& store,
                       size_t seed, uint64_t key, uint32_t chainLength, float energyPerStep) {
  const SeedQueue& s = store.seeds;
  const uint32_t n = std::min<uint32_t>(s.vertexCount[seed], uint32_t(kMaxChainVertices));
  uint8_t kinds[kMaxChainVertices];
  for (uint32_t j = 0; j < n; ++j) {
    chainVertices.copyRow(slot * kMaxChainVertices + j, store.vertices, s.vertexBegin[seed] + j);
    kinds[j] = store.vertices.kind[s.vertexBegin[seed] + j];
  }
  const Color c = store.contribution(seed);
  ChainQueue::Row chain;  // no cached f or tail yet (MutationKind::None = 0)
  chain.key = key;
  chain.stepsLeft = chainLength;
  chain.vertexCount = uint8_t(n);
  chain.signature = packSignature(kinds, int(n));
  chain.filmX = s.filmX[seed];
  chain.filmY = s.filmY[seed];
  chain.color = c / luminance(c);
  chain.energy = energyPerStep;
  chain.runPixel = kNoPixel;
  chain.largeWeight = -1;  // computed by the first large step that needs it
  chains.setRow(slot, chain);
}

}  // namespace erpt
