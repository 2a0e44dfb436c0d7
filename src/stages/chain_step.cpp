#include "stages/chain_step.h"

#include <atomic>

#include "core/parallel.h"

namespace erpt {

namespace {

size_t raysInFlight(const RayQueue& rays, IndexRange r) {
  size_t n = 0;
  for (size_t i = r.begin; i < r.end; ++i) n += rays.tnear[i] <= rays.tfar[i];
  return n;
}

// Dense batches. After the first bounce only the proposals walking a specular chain (or
// through a perturbed direction) still have a ray, and only those that reached their last
// regenerated vertex have a connection: instead of handing Embree and the trace stage the
// whole queue with most rows disabled, their rays are gathered into consecutive rows of
// `denseRays`, and `denseSlots` says which chain slot each row belongs to. Gathering keeps slot
// order, so every proposal's arithmetic (and the image) is the same as without it.

// Rows [0, n) of `denseRays` / `denseSlots`: the slots of `q.proposals` in state `state`, with
// their ray from `from` (row = slot).
size_t gatherBySlot(StepQueues& q, const RayQueue& from, uint8_t state) {
  q.denseSlots.clear();
  for (size_t i = 0; i < q.chains.size(); ++i) {
    if (q.proposals.state[i] != state) continue;
    q.denseRays.copyRow(q.denseSlots.size(), from, i);
    q.denseSlots.push_back(uint32_t(i));
  }
  return q.denseSlots.size();
}

// Keeps the rows of `denseRays` whose proposal still walks, moved down in order.
size_t keepWalking(StepQueues& q) {
  size_t kept = 0;
  for (size_t k = 0; k < q.denseSlots.size(); ++k) {
    const uint32_t slot = q.denseSlots[k];
    if (q.proposals.state[slot] != kProposalWalking) continue;
    if (kept != k) q.denseRays.copyRow(kept, q.denseRays, k);
    q.denseSlots[kept++] = slot;
  }
  q.denseSlots.resize(kept);
  return kept;
}

}  // namespace

uint64_t ChainStep::propose(StepQueues& q) const {
  forEachRange("chain mutate", q.chains.size(), grain, [&](IndexRange r) {
    stageChainMutate(ctx, q.chains, q.chainVertices, q.proposals, q.rays, r, policy);
    for (size_t i = r.begin; i < r.end; ++i) disableRay(q.shadowRays, i);
  }, times);
  const uint64_t ownRays = policy ? policy->startOwnProposals(ctx, q, times) : 0;
  const uint64_t bidirectionalRays = stageChainBidirectional(tracer, ctx, q, grain, times);
  return ownRays + bidirectionalRays + traceAndConnect(q);
}

uint64_t ChainStep::traceAndConnect(StepQueues& q) const {
  const size_t c = q.chains.size();
  std::atomic<uint64_t> rays{0};
  std::atomic<size_t> walking{0};
  // First bounce: nearly every slot has a ray, the queue is traced as it is.
  forEachRange("chain intersect", c, grain, [&](IndexRange r) {
    const size_t traced = raysInFlight(q.rays, r);
    rays += traced;
    if (traced > 0) tracer.intersect(q.rays, q.hits, r, RayCoherence::Incoherent);
  }, times);
  forEachRange("chain trace", c, grain, [&](IndexRange r) {
    walking += stageChainTrace(ctx, q.chains, q.chainVertices, q.proposals, q.proposalVertices, q.rays, q.hits,
                              q.shadowRays, r);
  }, times);
  // Later bounces (a walk bounces at most once per vertex of the longest path): dense.
  if (walking > 0) {
    size_t n = gatherBySlot(q, q.rays, kProposalWalking);
    for (int pass = 1; pass < kMaxChainVertices && n > 0; ++pass) {
      rays += n;
      forEachRange("chain intersect", n, grain, [&](IndexRange r) {
        tracer.intersect(q.denseRays, q.denseHits, r, RayCoherence::Incoherent);
      }, times);
      forEachRange("chain trace", n, grain, [&](IndexRange r) {
        stageChainTrace(ctx, q.chains, q.chainVertices, q.proposals, q.proposalVertices, q.denseRays, q.denseHits,
                       q.shadowRays, r, q.denseSlots.data());
      }, times);
      n = keepWalking(q);
    }
  }
  rays += stageChainManifold(tracer, ctx, q, grain, times);
  const size_t connections = gatherBySlot(q, q.shadowRays, kProposalConnecting);
  rays += connections;
  forEachRange("chain connect", connections, grain, [&](IndexRange r) {
    stageChainConnect(tracer, q.denseRays, q.proposals, r, q.denseSlots.data());
  }, times);
  return rays;
}

void ChainStep::accept(StepQueues& q, StepCounters& counters) const {
  forEachRange("chain accept", q.chains.size(), grain, [&](IndexRange r) {
    if (policy) policy->selectionRatios(q.chains, q.proposals, r);
    stageChainAccept(ctx, q.chains, q.chainVertices, q.proposals, q.proposalVertices, q.deposits, counters, r);
  }, times);
}

}  // namespace erpt
