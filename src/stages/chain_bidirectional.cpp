// The bidirectional mutation's stage (mutations/bidirectional.h): after the mutate stage, the
// proposals waiting in state kProposalBidirectional draw their plan, walk from both ends in
// dense ray batches (one bounce of every walk per batch), connect the walks' ends in one
// occlusion stream, and leave complete with their acceptance ratio, or rejected.
//
// Proposal columns while walking: regenFirst / regenLast the new vertices' range [l + 1,
// l + added], connectTo the eye-side end of the connection (l + eyeSide), cursor the vertex the
// next ray makes, walk +1 on the eye side, -1 on the light side, vertexCount the proposed
// path's length. The proposed path is written whole into the slot's proposal vertex rows.
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/rng.h"
#include "kernels/surface_vertex.h"
#include "models/surface.h"
#include "mutations/bidirectional.h"
#include "mutations/path_factors.h"
#include "stages/chain_stages.h"
#include "stages/mlt_stages.h"

namespace erpt {

namespace {

// The stream of the mutation's own random numbers: dimensions 0-3 the plan, then six per
// vertex j of the proposed path (the sample that makes it).
uint64_t bidirectionalKey(const ChainQueue& chains, size_t i) {
  return streamKey(chains.key[i], chains.step[i], 0x626964697265ull);
}
constexpr uint32_t kPlanDims = 4, kDimsPerVertex = 6;
// The shortest connection, relative to the coordinates' magnitude (a few times the ray
// origins' offset, surface.h's offsetOrigin).
constexpr float kMinEdge = 1e-4f;
uint32_t vertexDim(int j) { return kPlanDims + kDimsPerVertex * uint32_t(j); }

void reject(ProposalQueue& p, size_t i, RejectReason why) {
  p.state[i] = kProposalRejected;
  p.reason[i] = why;
}

size_t rowOf(size_t slot, int j) { return slot * kMaxChainVertices + size_t(j); }

// Draws slot i's plan and copies the kept vertices of y into the proposal's rows.
void startOne(const StepConfig& ctx, const ChainQueue& chains, const VertexQueue& chainVertices,
              ProposalQueue& proposals, VertexQueue& proposalVertices, size_t i) {
  PathVertex y[kMaxChainVertices];
  const int n = loadChainPath(chains, chainVertices, i, y);
  uint8_t kinds[kMaxChainVertices];
  for (int j = 0; j < n; ++j) kinds[j] = y[j].kind;
  BidirectionalPlan plan;
  if (!bidirectionalApplies(kinds, n) ||
      !drawBidirectionalPlan(n, lightDeletable(ctx.measure, y, n), ctx.lengths, bidirectionalKey(chains, i), 0,
                             plan)) {
    reject(proposals, i, kRejectNoMutation);
    return;
  }
  const int nz = proposedVertices(n, plan);
  for (int j = 0; j <= plan.l; ++j) proposalVertices.copyRow(rowOf(i, j), chainVertices, rowOf(i, j));
  for (int j = plan.m; j < n; ++j)
    proposalVertices.copyRow(rowOf(i, j - plan.deleted() + plan.added), chainVertices, rowOf(i, j));
  proposals.vertexCount[i] = uint8_t(nz);
  proposals.regenFirst[i] = int8_t(plan.l + 1);
  proposals.regenLast[i] = int8_t(plan.l + plan.added);
  proposals.connectTo[i] = int8_t(plan.l + plan.eyeSide);
  proposals.filmX[i] = chains.filmX[i];
  proposals.filmY[i] = chains.filmY[i];
  proposals.walk[i] = plan.eyeSide > 0 ? +1 : -1;
  proposals.cursor[i] = int8_t(plan.eyeSide > 0 ? plan.l + 1 : plan.l + plan.added);
}

bool connectable(const PathVertex& v, const Scene& scene) {
  if (v.kind == kLightVertex || v.kind == kEnvironmentVertex) return true;
  return v.material >= 0 && !scene.materials[size_t(v.material)].isPureSpecular();
}

// Slot i's next ray, written to row k of `rays`: true when there is one; otherwise the
// proposal is connecting (its connection ray in row k of `connections`) or rejected.
bool nextRay(const StepConfig& ctx, const ChainQueue& chains, ProposalQueue& proposals, VertexQueue& zRows, size_t i,
             RayQueue& rays, size_t k, RayQueue& connections) {
  const MeasureContext& c = ctx.measure;
  const uint64_t key = bidirectionalKey(chains, i);
  const int nz = proposals.vertexCount[i], joinAt = proposals.connectTo[i];
  for (;;) {
    const int j = proposals.cursor[i];
    if (proposals.walk[i] > 0 && j > joinAt) {  // the eye side is done: the light side's turn
      proposals.walk[i] = -1;
      proposals.cursor[i] = proposals.regenLast[i];
      continue;
    }
    const uint32_t d = vertexDim(j);
    if (proposals.walk[i] > 0) {
      // Vertex j from vertex j - 1: a film position uniform over the image from the eye.
      PathVertex from = loadPathVertex(zRows, rowOf(i, j - 1));
      if (j == 1) {
        const float fx = float(uniformDouble(key, d) * c.film.width()), fy = float(uniformDouble(key, d + 1) * c.film.height());
        if (!(c.film.density(fx, fy) > 0)) return reject(proposals, i, kRejectOffFilm), false;
        const Camera::Ray r = c.camera.hasLens() ? c.camera.generateRayFrom(from.p, fx, fy) : c.camera.generateRay(fx, fy);
        proposals.filmX[i] = fx;
        proposals.filmY[i] = fy;
        setRay(rays, k, r.origin, r.direction, r.tnear, r.tfar);
        return true;
      }
      const PathVertex before = loadPathVertex(zRows, rowOf(i, j - 2));
      Vec3 wo;
      if (!factors::sampleAt(c, from, directionBetween(from, before), uniformFloat(key, d), uniformFloat(key, d + 1),
                             uniformFloat(key, d + 2), wo))
        return reject(proposals, i, kRejectZero), false;
      storePathVertex(zRows, rowOf(i, j - 1), from);  // its kind: the lobe taken
      setRay(rays, k, offsetOrigin(from.p, from.ng, wo), wo, 0.0f, std::numeric_limits<float>::infinity());
      return true;
    }
    if (j <= joinAt) {
      // Both walks are done: connect vertex joinAt to joinAt + 1.
      PathVertex e = loadPathVertex(zRows, rowOf(i, joinAt)), l = loadPathVertex(zRows, rowOf(i, joinAt + 1));
      if (!connectable(e, c.scene) || e.kind == kLightVertex || !connectable(l, c.scene))
        return reject(proposals, i, kRejectZero), false;
      e.kind = kNonSpecularVertex;
      if (l.kind != kLightVertex && l.kind != kEnvironmentVertex) l.kind = kNonSpecularVertex;
      storePathVertex(zRows, rowOf(i, joinAt), e);
      storePathVertex(zRows, rowOf(i, joinAt + 1), l);
      const bool environment = l.kind == kEnvironmentVertex;
      // A light-side walk through a Dirac vertex can land back on the eye side's end (y's own
      // vertex, when nothing was deleted there): a zero-length edge, whose f is unbounded.
      // Such paths are outside the chains' space both ways.
      if (!environment && !(length(l.p - e.p) > kMinEdge * std::max({1.0f, std::abs(e.p.x), std::abs(e.p.y), std::abs(e.p.z)})))
        return reject(proposals, i, kRejectZero), false;
      const Vec3 dir = directionBetween(e, l);
      setConnectionRay(connections, k, e, environment ? Vec3(0.0f) : offsetOrigin(l.p, l.ng, -dir), environment, dir);
      proposals.state[i] = kProposalConnecting;
      return false;
    }
    if (j == nz - 1) {
      // A new light point (emission sampling); its direction is sampled for the next vertex.
      EmissionSample e;
      if (!c.lights.sampleEmission(uniformDouble(key, d), uniformFloat(key, d + 1), uniformFloat(key, d + 2), 0.5f, 0.5f,
                                   e) ||
          e.infinite)
        return reject(proposals, i, kRejectZero), false;
      PathVertex light;
      light.p = e.origin;
      light.ns = light.ng = e.deltaPosition ? Vec3(0.0f) : e.normal;
      light.kind = kLightVertex;
      light.emitter = e.emitter;
      storePathVertex(zRows, rowOf(i, j), light);
      proposals.cursor[i] = int8_t(j - 1);
      continue;
    }
    // Vertex j from vertex j + 1: the light's emission direction, or adjoint BSDF sampling.
    PathVertex from = loadPathVertex(zRows, rowOf(i, j + 1));
    Vec3 wo;
    if (j + 1 == nz - 1) {
      float pdf;
      if (from.kind != kLightVertex ||
          !c.lights.sampleEmissionDirection(from.emitter, from.ng, uniformFloat(key, d), uniformFloat(key, d + 1), wo, pdf))
        return reject(proposals, i, kRejectZero), false;
    } else {
      const PathVertex after = loadPathVertex(zRows, rowOf(i, j + 2));
      if (!factors::sampleAt(c, from, directionBetween(from, after), uniformFloat(key, d), uniformFloat(key, d + 1),
                             uniformFloat(key, d + 2), wo))
        return reject(proposals, i, kRejectZero), false;
      storePathVertex(zRows, rowOf(i, j + 1), from);
    }
    setRay(rays, k, offsetOrigin(from.p, from.ng, wo), wo, 0.0f, std::numeric_limits<float>::infinity());
    return true;
  }
}

// The hit of slot i's walk ray (row k): the new vertex at the cursor, then the cursor moves on.
void storeHit(const Scene& scene, ProposalQueue& proposals, VertexQueue& zRows, size_t i, const HitQueue& hits,
              size_t k) {
  if (hits.geomID[k] == kNoHit || hits.geomID[k] == kRefusedRay) return reject(proposals, i, kRejectMissed);
  const SurfacePoint sp = surfaceAt(scene, hits.primID[k], hits.u[k], hits.v[k]);
  PathVertex v;
  setSurfaceVertex(v, sp, scene.materials[size_t(sp.material)]);
  const int j = proposals.cursor[i];
  storePathVertex(zRows, rowOf(i, j), v);
  proposals.cursor[i] = int8_t(j + proposals.walk[i]);
}

// A connected proposal: its f, domain, colour and acceptance ratio.
void finishOne(const StepConfig& ctx, const ChainQueue& chains, const VertexQueue& chainVertices,
               ProposalQueue& proposals, const VertexQueue& zRows, size_t i) {
  PathVertex y[kMaxChainVertices], z[kMaxChainVertices];
  uint8_t kinds[kMaxChainVertices];
  const int ny = loadChainPath(chains, chainVertices, i, y), nz = proposals.vertexCount[i];
  for (int j = 0; j < nz; ++j) {
    loadPathVertex(zRows, rowOf(i, j), z[j]);
    kinds[j] = z[j].kind;
  }
  const float fx = proposals.filmX[i], fy = proposals.filmY[i];
  const Color f = bidirectionalContribution(ctx.measure, z, nz, fx, fy);
  const float lum = luminance(f);
  if (!(lum > 0) || !std::isfinite(lum)) return reject(proposals, i, kRejectZero);
  // The chains' domain: MLT's (its large step's W > 0, kept for the chain), or every
  // perturbation's f positive.
  const float w = ctx.largeSteps ? mltDomainWeight(ctx, z, nz, fx, fy) : -1.0f;
  if (ctx.largeSteps ? !(w > 0) : pathHasZeroContribution(ctx, z, nz, fx, fy))
    return reject(proposals, i, kRejectOutsideDomain);
  BidirectionalPlan plan;
  plan.l = proposals.regenFirst[i] - 1;
  plan.added = proposals.regenLast[i] - plan.l;
  plan.m = plan.l + 1 + (ny - nz + plan.added);
  plan.eyeSide = proposals.connectTo[i] - plan.l;
  const double r = bidirectionalRatio(ctx.measure, ctx.lengths, y, ny, chains.filmX[i], chains.filmY[i], z, nz, fx,
                                      fy, plan);
  if (!(r > 0)) return reject(proposals, i, kRejectIrreversible);
  proposals.ratio[i] = float(std::min(r, 1e30));
  proposals.colorSet(i, f / lum);
  proposals.signature[i] = packSignature(kinds, nz);
  proposals.largeWeight[i] = w;
  proposals.state[i] = kProposalComplete;
}

}  // namespace

uint64_t stageChainBidirectional(const Tracer& tracer, const StepConfig& ctx, StepQueues& q, size_t grain,
                                 StageTimes* times) {
  const std::vector<uint32_t> slots = slotsInState(q.proposals, kProposalBidirectional);
  if (slots.empty()) return 0;
  forEachRange("bidirectional start", slots.size(), grain, [&](IndexRange r) {
    for (size_t k = r.begin; k < r.end; ++k)
      startOne(ctx, q.chains, q.chainVertices, q.proposals, q.proposalVertices, slots[k]);
  }, times);
  // Walks: each batch traces one ray of every proposal still walking. Walk rays go to
  // denseRays, connection rays to shadowRays, both in row k of the slot's place in `slots`.
  uint64_t rays = 0;
  std::vector<uint8_t> hasRay(slots.size());
  for (int pass = 0; pass <= kMaxChainVertices; ++pass) {
    size_t walking = 0;
    forEachRange("bidirectional walk", slots.size(), grain, [&](IndexRange r) {
      for (size_t k = r.begin; k < r.end; ++k) {
        const size_t i = slots[k];
        hasRay[k] = q.proposals.state[i] == kProposalBidirectional &&
                    nextRay(ctx, q.chains, q.proposals, q.proposalVertices, i, q.denseRays, k, q.shadowRays);
        if (!hasRay[k]) disableRay(q.denseRays, k);
        if (q.proposals.state[i] != kProposalConnecting) disableRay(q.shadowRays, k);
      }
    }, times);
    for (uint8_t h : hasRay) walking += h;
    if (walking == 0) break;
    rays += walking;
    forEachRange("bidirectional intersect", slots.size(), grain, [&](IndexRange r) {
      tracer.intersect(q.denseRays, q.denseHits, r, RayCoherence::Incoherent);
      for (size_t k = r.begin; k < r.end; ++k)
        if (hasRay[k]) storeHit(ctx.measure.scene, q.proposals, q.proposalVertices, slots[k], q.denseHits, k);
    }, times);
  }
  // The connections (every proposal is connecting, rejected, or was left walking by a path
  // longer than the passes allow, which cannot happen: each pass adds a vertex).
  forEachRange("bidirectional connect", slots.size(), grain, [&](IndexRange r) {
    for (size_t k = r.begin; k < r.end; ++k)
      if (q.proposals.state[slots[k]] == kProposalBidirectional) reject(q.proposals, slots[k], kRejectMissed);
    stageChainConnect(tracer, q.shadowRays, q.proposals, r, slots.data());
    for (size_t k = r.begin; k < r.end; ++k) {
      const size_t i = slots[k];
      if (q.proposals.state[i] == kProposalComplete)
        finishOne(ctx, q.chains, q.chainVertices, q.proposals, q.proposalVertices, i);
      disableRay(q.shadowRays, k);
    }
  }, times);
  for (uint32_t i : slots) disableRay(q.rays, i);
  return rays;
}

}  // namespace erpt
