// Trace stage: one bounce of every walking proposal, after the intersect stream. The walk
// is the same for every mutation: from `cursor` in direction `walk` it must meet the current
// path's kinds of vertices and take its specular lobes; at non-specular vertices before the
// last regenerated one it perturbs the direction (the lens perturbation's D vertices followed
// by S); at the last regenerated vertex it connects to `connectTo` (the eye: film position by
// projection; a fixed vertex), or, with nothing to connect to, it must have traced into the
// light; or, with a specular chain before `connectTo`, it leaves the proposal to the manifold
// stage (chain_manifold.cpp). The mutation's start wrote these numbers (mutation.h).
#include "models/bsdf.h"
#include "kernels/surface_vertex.h"
#include "stages/chain_stages.h"
#include "core/rng.h"
#include "models/surface.h"
#include "tracer/tracer.h"

namespace erpt {

namespace {

void complete(ProposalQueue& p, RayQueue& rays, size_t i, size_t ray) {
  p.state[i] = kProposalComplete;
  disableRay(rays, ray);
}

}  // namespace

size_t stageChainTrace(const StepConfig& ctx, const ChainQueue& chains, const VertexQueue& chainVertices,
                      ProposalQueue& proposals, VertexQueue& proposalVertices, RayQueue& rays, const HitQueue& hits,
                      RayQueue& shadowRays, IndexRange range, const uint32_t* slotOf) {
  const MeasureContext& mc = ctx.measure;
  const Scene& scene = mc.scene;
  size_t walking = 0;
  for (size_t k = range.begin; k < range.end; ++k) {
    // Row k of the ray and hit queues belongs to chain slot i.
    const size_t i = slotOf ? slotOf[k] : k;
    if (proposals.state[i] != kProposalWalking) continue;
    disableRay(shadowRays, i);
    const int n = chains.vertexCount[i];
    const int j = proposals.cursor[i], walk = proposals.walk[i];
    // The walk ends at the far end of the regenerated range from where it started.
    const bool last = j == (walk > 0 ? proposals.regenLast[i] : proposals.regenFirst[i]);
    const int connectTo = proposals.connectTo[i];
    // The current path's vertices j - 1, j, j + 1 (all a walk step looks at), loaded only by
    // the branches that read more than vertex j's kind (most steps do not).
    const size_t chainRow = i * kMaxChainVertices + size_t(j);
    auto loadWindow = [&](PathVertex* window) {
      for (int w = 0; w < 3; ++w)
        if (j - 1 + w >= 0 && j - 1 + w < n) loadPathVertex(chainVertices, chainRow - 1 + size_t(w), window[w]);
    };
    const uint8_t expectedKind = chainVertices.kind[chainRow];
    const Vec3 origin = rays.orgAt(k);
    const Vec3 dir = normalize(rays.dirAt(k));
    const size_t row = chainRow;
    // Reaching the light by tracing ends the walk only where the proposal has nothing to
    // connect to.
    const bool tracesToLight = last && connectTo < 0;

    PathVertex z;
    if (hits.geomID[k] == kRefusedRay) {  // T = 0: a proposal we cannot trace is rejected
      rejectProposal(proposals, rays, i, kRejectMissed, k);
      continue;
    }
    if (hits.geomID[k] == kNoHit) {
      if (!tracesToLight || expectedKind != kEnvironmentVertex) {
        rejectProposal(proposals, rays, i, kRejectMissed, k);
        continue;
      }
      z.p = origin + dir * 1e6f;
      z.ns = z.ng = -dir;
      z.kind = kEnvironmentVertex;
      z.emitter = chainVertices.emitter[chainRow];
      storePathVertex(proposalVertices, row, z);
      complete(proposals, rays, i, k);
      continue;
    }
    const SurfacePoint sp = surfaceAt(scene, hits.primID[k], hits.u[k], hits.v[k]);
    const Material& m = scene.materials[size_t(sp.material)];
    setSurfaceVertex(z, sp, m);
    z.kind = expectedKind;

    if (expectedKind == kLightVertex) {
      if (!tracesToLight || isBlack(mc.lights.emitted(sp, -dir))) {
        rejectProposal(proposals, rays, i, kRejectKindChanged, k);
        continue;
      }
      storePathVertex(proposalVertices, row, z);
      complete(proposals, rays, i, k);
      continue;
    }
    // Specular vertices need a Dirac lobe (plastic's coat has one too), non-specular ones a
    // non-Dirac component.
    const bool kindMatches = expectedKind == kSpecularVertex     ? m.hasSpecular()
                             : expectedKind == kNonSpecularVertex ? !m.isPureSpecular()
                                                                  : false;
    if (!kindMatches) {
      rejectProposal(proposals, rays, i, kRejectKindChanged, k);
      continue;
    }
    storePathVertex(proposalVertices, row, z);

    if (expectedKind == kSpecularVertex) {
      // Follow the same lobe (reflection or transmission) as the current path.
      PathVertex window[3];
      loadWindow(window);
      Vec3 wo;
      if (last || !specularDirection(m, sp.shading.toLocal(-dir), reflectsAt(window, 1), wo)) {
        rejectProposal(proposals, rays, i, kRejectKindChanged, k);
        continue;
      }
      const Vec3 next = sp.shading.toWorld(wo);
      setRay(rays, k, offsetOrigin(sp.position, sp.geometricNormal, next), next, 0.0f,
             std::numeric_limits<float>::infinity());
      proposals.cursor[i] = int8_t(j + walk);
      ++walking;
      continue;
    }

    // A non-specular vertex.
    if (!last) {
      // Perturb the current path's direction here and walk on through the specular chain.
      PathVertex window[3];
      loadWindow(window);
      const PathVertex& next = window[1 + walk];
      const uint64_t key = chains.key[i];
      const uint32_t step = chains.step[i];
      const Vec3 d = perturbDirection(directionBetween(window[1], next), uniformFloat(key, stepDim(step, kDimPerturb + 2 * j)),
                                      uniformFloat(key, stepDim(step, kDimPerturb + 2 * j + 1)));
      setRay(rays, k, offsetOrigin(z.p, z.ng, d), d, 0.0f, std::numeric_limits<float>::infinity());
      proposals.cursor[i] = int8_t(j + walk);
      ++walking;
      continue;
    }
    if (connectTo == 0) {
      // Connect to the eye (rule 5), the current path's vertex 0 (the pinhole, or its lens
      // point, which stays fixed): the film position is where z projects from there.
      const Vec3 eye = chainVertices.pAt(i * kMaxChainVertices);
      float fx, fy;
      if (!mc.camera.projectFrom(eye, z.p, fx, fy) || !(mc.film.density(fx, fy) > 0)) {
        rejectProposal(proposals, rays, i, kRejectOffFilm, k);
        continue;
      }
      proposals.filmX[i] = fx;
      proposals.filmY[i] = fy;
      setConnectionRay(shadowRays, i, z, eye, false, normalize(eye - z.p));
    } else if (connectTo > j + 1) {
      // A specular chain lies between this vertex and the fixed one: the manifold stage walks it.
      proposals.state[i] = kProposalManifold;
      disableRay(rays, k);
      continue;
    } else if (connectTo > 0) {
      // Connect to the current path's fixed vertex, which stays where it is.
      // (Its columns read straight: a PathVertex copied out and read back stalls on store
      // forwarding.)
      const size_t target = i * kMaxChainVertices + size_t(connectTo);
      const bool environment = chainVertices.kind[target] == kEnvironmentVertex;
      const Vec3 targetP = chainVertices.pAt(target);
      const Vec3 d = environment ? -chainVertices.nsAt(target) : normalize(targetP - z.p);
      setConnectionRay(shadowRays, i, z, environment ? Vec3(0.0f) : offsetOrigin(targetP, chainVertices.ngAt(target), -d),
                       environment, d);
    } else {
      rejectProposal(proposals, rays, i, kRejectKindChanged, k);  // the walk should have reached the light
      continue;
    }
    proposals.state[i] = kProposalConnecting;
    disableRay(rays, k);
  }
  return walking;
}

}  // namespace erpt
