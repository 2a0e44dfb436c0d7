// Manifold stage (chain_stages.h), after the trace stage: the manifold perturbation's proposals
// whose eye walk has reached the first non-specular vertex b of the new path (the proposal's
// regenerated vertex regenLast) walk the current path's specular chain from the fixed vertex c
// (connectTo) until it ends at the new b, then walk back to check that z can propose y, and
// measure the chain's |d omega_b / dA_c| at y and z (mutations/manifold.cpp says why). Each
// range of slots walks in lockstep: every Newton step of its walks is one batch of rays for
// the tracer's streams (kernels/manifold_retrace.h); the solves are per chain.
#include <algorithm>
#include <atomic>
#include <cmath>

#include "kernels/manifold_retrace.h"
#include "kernels/surface_vertex.h"
#include "models/surface.h"
#include "mutations/path_factors.h"
#include "stages/chain_stages.h"

namespace erpt {

namespace {

DVec3 d3(Vec3 v) { return {v.x, v.y, v.z}; }
double norm(DVec3 a) { return std::sqrt(dot(a, a)); }

// Newton steps a walk may take. A reachable target is reached in 3 to 6 (measured on the default
// scene); a walk still going after this many is walking towards the edge of the chain's
// footprint (a target the chain cannot reach), halving its step each time.
constexpr int kWalkSteps = 12;
static_assert(kMaxChainVertices <= kMaxManifoldVertices, "a chain's specular chain must fit a walk's");

void reject(ProposalQueue& p, size_t i, RejectReason why) {
  p.state[i] = kProposalRejected;
  p.reason[i] = why;
}

// What one proposal's walks need: the slot, its b and c, y's chain (c first, b last), the
// forward and backward walks.
struct ChainWalks {
  size_t slot;
  int b, c;
  ManifoldChain chainY;
  ManifoldWalk forward, back;
  Vec3 ngB;                // y's geometric normal at b
  double solidAngleY = 0;  // |d omega_b / dA_c| at y
  bool ok = true;
};

// A range's walks and the retracer's rays, kept per thread (a chain step allocates nothing
// once they are warm).
struct WalkScratch {
  std::vector<ChainWalks> walks;
  std::vector<ManifoldChain> chains;
  std::vector<uint8_t> located;
  std::vector<ManifoldWalk*> going;
};

// The fixed end c as the walk sees it: its position and the normal of the generalised geometry
// term's cosine (the geometric one; a point light's points towards the chain, so that its
// cosine is 1).
ManifoldVertex fixedEnd(const MeasureContext& mc, const PathVertex& end, const PathVertex& next) {
  ManifoldVertex v;
  v.p = d3(end.p);
  if (factors::isPointLight(mc, end)) {
    const DVec3 d = d3(next.p) - v.p;
    v.n = d * (1.0 / norm(d));
  } else {
    v.n = d3(end.ng);
  }
  return v;
}

// The chain's interaction at y's specular vertex j, as y has it: reflection or refraction, and
// the index of refraction. False where the walk has no rule: a thin sheet's transmission, which
// does not bend, or any transmission that is not a smooth dielectric's.
bool setInteraction(const Scene& scene, const PathVertex* y, int j, ManifoldVertex& v) {
  const Material& m = scene.materials[size_t(y[j].material)];
  v.reflect = reflectsAt(y, j);
  v.eta = m.kind == BsdfKind::Dielectric ? double(m.relativeIOR()) : 1.0;
  return v.reflect || m.kind == BsdfKind::Dielectric;
}

// |d omega_b / dA_c| of a chain (c first, b last), with b's geometric normal: G / |cos_g at b|.
double solidAnglePerArea(const ManifoldChain& chain, Vec3 ngB) {
  const size_t n = chain.size() - 1;
  const DVec3 toNext = chain[n - 1].p - chain[n].p;
  const double cosB = std::abs(dot(toNext, d3(ngB))) / norm(toNext);
  const double g = generalizedGeometry(chain);
  return cosB > 0 && g > 0 ? g / cosB : 0.0;
}

void walkRange(const Tracer& tracer, const StepConfig& ctx, StepQueues& q, const std::vector<uint32_t>& slots,
               IndexRange r, std::atomic<uint64_t>& rays) {
  const MeasureContext& mc = ctx.measure;
  const Scene& scene = mc.scene;
  StreamRetracer retracer(tracer, scene);
  static thread_local WalkScratch scratch;
  const size_t count = r.end - r.begin;
  if (scratch.walks.size() < count) scratch.walks.resize(count), scratch.chains.resize(count);
  std::vector<ChainWalks>& walks = scratch.walks;
  PathVertex y[kMaxChainVertices];
  for (size_t k = 0; k < count; ++k) {
    ChainWalks& w = walks[k];
    w.ok = true;
    w.solidAngleY = 0;
    w.slot = slots[r.begin + k];
    w.b = q.proposals.regenLast[w.slot];
    w.c = q.proposals.connectTo[w.slot];
    loadChainPath(q.chains, q.chainVertices, w.slot, y);
    w.ngB = y[w.b].ng;
    // y's chain, c first: its fixed end, then the points where the tracer is to find the rest.
    ManifoldChain& chain = scratch.chains[k];
    chain.assign(1, fixedEnd(mc, y[w.c], y[w.c - 1]));
    for (int j = w.c - 1; j >= w.b; --j) {
      ManifoldVertex sought;
      if (j > w.b) w.ok &= setInteraction(scene, y, j, sought);
      sought.p = d3(y[j].p);
      chain.push_back(sought);
    }
  }
  // y's chain with the walk's data: its vertices found again by the tracer.
  retracer.locate(scratch.chains, count, scratch.located);
  std::vector<ManifoldWalk*>& going = scratch.going;
  going.clear();
  for (size_t k = 0; k < count; ++k) {
    ChainWalks& w = walks[k];
    w.chainY = scratch.chains[k];
    w.ok = w.ok && scratch.located[k];
    if (w.ok) w.solidAngleY = solidAnglePerArea(w.chainY, w.ngB);
    if (!(w.solidAngleY > 0)) {
      reject(q.proposals, w.slot, w.ok ? kRejectCurrentZero : kRejectNoWalk);
      w.ok = false;
      continue;
    }
    w.forward.chain = w.chainY;
    w.forward.target = d3(q.proposalVertices.pAt(w.slot * kMaxChainVertices + size_t(w.b)));
    w.forward.tolerance = manifoldTolerance(w.forward.target);
    w.forward.maxIterations = kWalkSteps;
    startManifoldWalk(w.forward);
    going.push_back(&w.forward);
  }
  retracer.walk(going);
  // Back from z to y's b: it must end on y's chain, not on another branch of the manifold.
  going.clear();
  for (size_t k = 0; k < count; ++k) {
    ChainWalks& w = walks[k];
    if (!w.ok) continue;
    if (!w.forward.result.converged) {
      reject(q.proposals, w.slot, kRejectNoWalk);
      w.ok = false;
      continue;
    }
    w.back.chain = w.forward.chain;
    w.back.target = w.chainY.back().p;
    w.back.tolerance = manifoldTolerance(w.back.target);
    w.back.maxIterations = kWalkSteps;
    startManifoldWalk(w.back);
    going.push_back(&w.back);
  }
  retracer.walk(going);
  for (size_t k = 0; k < count; ++k) {
    ChainWalks& w = walks[k];
    if (!w.ok) continue;
    const size_t i = w.slot;
    bool reversible = w.back.result.converged;
    for (size_t v = 1; reversible && v + 1 < w.chainY.size(); ++v)
      reversible = norm(w.back.chain[v].p - w.chainY[v].p) <= 1e3 * manifoldTolerance(w.chainY[v].p);
    if (!reversible) {
      reject(q.proposals, i, kRejectIrreversible);
      continue;
    }
    const ManifoldChain& chainZ = w.forward.chain;
    const size_t base = i * kMaxChainVertices;
    const double solidAngleZ = solidAnglePerArea(chainZ, q.proposalVertices.ngAt(base + size_t(w.b)));
    if (!(solidAngleZ > 0)) {
      reject(q.proposals, i, kRejectZero);
      continue;
    }
    // z's specular vertices, as the renderer's surface points of the walk's hits.
    for (int j = w.b + 1; j < w.c; ++j) {
      const ManifoldVertex& v = chainZ[size_t(w.c - j)];
      const SurfacePoint sp = surfaceAt(scene, v.primitive, v.hitU, v.hitV);
      PathVertex pv = loadPathVertex(q.chainVertices, base + size_t(j));
      setSurfaceVertex(pv, sp, scene.materials[size_t(sp.material)]);
      pv.kind = kSpecularVertex;
      storePathVertex(q.proposalVertices, base + size_t(j), pv);
    }
    q.proposals.regenLast[i] = int8_t(w.c - 1);
    q.proposals.measureRatio[i] = float(solidAngleZ / w.solidAngleY);
    q.proposals.state[i] = kProposalComplete;
  }
  rays += retracer.raysTraced();
}

}  // namespace

uint64_t stageChainManifold(const Tracer& tracer, const StepConfig& ctx, StepQueues& q, size_t grain,
                            StageTimes* times) {
  const std::vector<uint32_t> slots = slotsInState(q.proposals, kProposalManifold);
  if (slots.empty()) return 0;
  std::atomic<uint64_t> rays{0};
  forEachRange("chain manifold", slots.size(), std::max<size_t>(16, grain / 4), [&](IndexRange r) {
    walkRange(tracer, ctx, q, slots, r, rays);
  }, times);
  return rays;
}

}  // namespace erpt
