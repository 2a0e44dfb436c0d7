#include "erpt/chain_step.h"

#include <atomic>

#include "erpt/parallel.h"

namespace erpt {

namespace {

size_t raysInFlight(const RayQueue& rays, IndexRange r) {
  size_t n = 0;
  for (size_t i = r.begin; i < r.end; ++i) n += rays.tnear[i] <= rays.tfar[i];
  return n;
}

}  // namespace

uint64_t ChainStep::propose(ErptQueues& q) const {
  forEachRange("erpt mutate", q.chains.size(), grain, [&](IndexRange r) {
    stageErptMutate(ctx, q.chains, q.chainVertices, q.proposals, q.rays, r, chooser);
    for (size_t i = r.begin; i < r.end; ++i) disableRay(q.shadowRays, i);
  }, times);
  return traceAndConnect(q);
}

uint64_t ChainStep::traceAndConnect(ErptQueues& q) const {
  const size_t c = q.chains.size();
  std::atomic<uint64_t> rays{0};
  std::atomic<size_t> walking{0};
  // A walk bounces at most once per vertex of the longest path.
  for (int pass = 0; pass < kMaxChainVertices; ++pass) {
    forEachRange("erpt intersect", c, grain, [&](IndexRange r) {
      const size_t traced = raysInFlight(q.rays, r);
      rays += traced;
      // Later passes carry only the proposals still walking a specular chain: ranges without
      // any are not handed to Embree (their hits are not read).
      if (traced > 0) tracer.intersect(q.rays, q.hits, r, RayCoherence::Incoherent);
    }, times);
    forEachRange("erpt trace", c, grain, [&](IndexRange r) {
      walking += stageErptTrace(ctx, q.chains, q.chainVertices, q.proposals, q.proposalVertices, q.rays, q.hits,
                                q.shadowRays, r);
    }, times);
    if (walking.exchange(0) == 0) break;
  }
  forEachRange("erpt connect", c, grain, [&](IndexRange r) {
    rays += raysInFlight(q.shadowRays, r);
    stageErptConnect(tracer, q.shadowRays, q.proposals, r);
  }, times);
  return rays;
}

void ChainStep::accept(ErptQueues& q, ErptCounters& counters) const {
  forEachRange("erpt accept", q.chains.size(), grain, [&](IndexRange r) {
    if (chooser) chooser->selectionRatios(q.chains, q.proposals, r);
    stageErptAccept(ctx, q.chains, q.chainVertices, q.proposals, q.proposalVertices, q.deposits, counters, r);
  }, times);
}

}  // namespace erpt
