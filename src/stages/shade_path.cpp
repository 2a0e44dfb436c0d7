// Path tracer surface stage: emission (MIS-weighted), next-event estimation, BSDF sampling
// and Russian roulette for every live slot.
#include <limits>

#include "kernels/erpt_path.h"
#include "kernels/surface_vertex.h"
#include "core/rng.h"
#include "stages/shade_path_diffuse.h"
#include "stages/shade_path_miss.h"
#include "stages/stages.h"
#include "tracer/tracer.h"

namespace erpt {

namespace {

void addRadiance(PathQueue& p, uint32_t id, Color c) { p.radianceSet(id, p.radianceAt(id) + c); }

}  // namespace

void stageShadePath(const StageContext& ctx, PathQueue& paths, PathSlotQueue& slots, RayQueue& rays,
                    const HitQueue& hits, RayQueue& shadowRays, VertexHistory history, IndexRange range) {
  const Emitter* env = ctx.scene.environment();
  const bool recording = history.vertices != nullptr;
  // Plain diffuse hits go to the vector kernel, a packet at a time, and so do rays escaping
  // into an environment map; the rest run the body below. On scenes without triangle, sphere or
  // environment lights no hit qualifies, and trying each would cost a light pick.
  const bool vector = ctx.vectorShading && ctx.lights.hasPacketLights();
  DiffuseShadePacket diffuse;
  EnvironmentMissPacket misses(ctx);
  const bool vectorMisses = ctx.vectorShading && misses.active();
  for (size_t k = range.begin; k < range.end; ++k) {
    if (vector && diffuse.add(ctx, paths, slots, hits, k)) {
      if (diffuse.full()) diffuse.shade(ctx, paths, slots, rays, hits, shadowRays, history);
      continue;
    }
    const uint32_t id = slots.path[k];
    const size_t vertex = history.base + k;
    slots.alive[k] = 0;
    slots.neeSet(k, Color(0.0f));
    if (recording) {
      slots.emitWeight[k] = slots.neeWeight[k] = 0;
      slots.pLengthHere[k] = paths.pLength[id];
    }
    disableRay(shadowRays, k);
    const uint32_t depth = paths.depth[id];  // segments so far, including the ray just traced
    const Color throughput = paths.throughputAt(id);
    const Vec3 dir = rays.dirAt(k);
    const Vec3 prev = paths.prevAt(id);
    const float prevPdf = paths.prevPdf[id];

    if (hits.geomID[k] == kRefusedRay) {  // the sample is invalid: the film drops and counts it
      paths.radianceSet(id, Color(std::numeric_limits<float>::quiet_NaN()));
      continue;
    }
    if (hits.geomID[k] == kNoHit) {
      if (!env || int(depth) < ctx.minSegments) continue;
      if (vectorMisses) {
        misses.add(k);
        if (misses.full()) misses.shade(ctx, paths, slots, rays, history);
        continue;
      }
      float lightPdf;
      const Color le = ctx.lights.environmentRadianceAndPdf(*env, dir, lightPdf);
      finishEnvironmentMiss(ctx, paths, slots, rays, history, k, *env, le, lightPdf);
      continue;
    }
    const SurfacePoint sp = surfaceAt(ctx.scene, hits.primID[k], hits.u[k], hits.v[k]);
    const Material& m = ctx.scene.materials[sp.material];
    if (recording) {
      VertexQueue::Row v;  // the whole row: pdfForward 0 and the parent link are written too
      setSurfaceVertex(v, sp, m);
      v.parent = paths.lastVertex[id];
      history.vertices->setRow(vertex, v);
      paths.lastVertex[id] = int32_t(vertex);
    }
    const Color le = int(depth) >= ctx.minSegments ? ctx.lights.emitted(sp, -dir) : Color(0.0f);
    if (!isBlack(le)) {
      float lightPdf = prevPdf > 0 ? ctx.lights.pdfSolidAngle(sp, prev) : 0.0f;
      const float w = emitterHitWeight(prevPdf, lightPdf);
      addRadiance(paths, id, throughput * le * w);
      if (recording) {
        slots.emitWeight[k] = w;
        slots.emitSet(k, throughput * le);
      }
    }
    // A path of maxDepth segments can grow no further (-1: unbounded).
    if (ctx.maxDepth >= 0 && depth >= uint32_t(ctx.maxDepth)) continue;

    const uint64_t key = paths.key[id];
    const SurfaceColors colors = ctx.scene.surfaceColors(sp.material, sp.u, sp.v);
    const Vec3 wi = sp.shading.toLocal(-dir);

    LightConnection lc;
    if (int(depth) + 1 >= ctx.minSegments &&
        connectToLight(ctx.lights, sp, m, colors, wi, drawDouble(ctx, key, bounceDim(depth, kLightPick)),
                       drawFloat(ctx, key, bounceDim(depth, kLight1)), drawFloat(ctx, key, bounceDim(depth, kLight2)), lc)) {
      slots.neeSet(k, throughput * lc.contribution);
      setRay(shadowRays, k, lc.origin, lc.direction, 0.0f, lc.tfar);
      if (recording) {
        slots.neeWeight[k] = lc.misWeight;
        slots.neeBsdfPdf[k] = lc.bsdfPdf;
        slots.neeLightPdf[k] = lc.light.pdfLight;
        slots.neeLightKind[k] = lc.light.environment ? kEnvironmentVertex : kLightVertex;
        slots.neeLightEmitter[k] = lc.light.emitter;
        slots.neeLightSet(k, lc.light.environment ? environmentPoint(sp.position, lc.direction) : lc.light.position);
        slots.neeLightNSet(k, lc.light.environment ? -lc.direction : lc.light.normal);
      }
    }

    BsdfSample bs;
    if (!bsdfSample(m, colors, wi, drawFloat(ctx, key, bounceDim(depth, kLobe)), drawFloat(ctx, key, bounceDim(depth, kBsdf1)),
                    drawFloat(ctx, key, bounceDim(depth, kBsdf2)), bs) ||
        isBlack(bs.weight))
      continue;
    Color next = throughput * bs.weight;
    if (recording) {
      history.vertices->pdfForward[vertex] = bs.pdf;  // for a Dirac lobe: its probability p_s
      history.vertices->kind[vertex] = bs.delta ? kSpecularVertex : kNonSpecularVertex;
    }
    paths.etaSquared[id] *= bs.eta * bs.eta;
    if (int(depth) >= ctx.rrDepth) {
      // Russian roulette: survive with probability q, reweight by 1/q (unbiased).
      const float q = russianRouletteSurvival(next, paths.etaSquared[id]);
      if (!(drawDouble(ctx, key, bounceDim(depth, kRoulette)) < q)) continue;
      next = next / q;
      paths.pLength[id] *= q;
    }
    paths.throughputSet(id, next);
    paths.prevPdf[id] = bs.delta ? 0.0f : bs.pdf;
    paths.prevSet(id, sp.position);
    paths.depth[id] = depth + 1;
    const Vec3 wo = sp.shading.toWorld(bs.wo);
    setRay(rays, k, offsetOrigin(sp.position, sp.geometricNormal, wo), wo, 0.0f, std::numeric_limits<float>::infinity());
    slots.alive[k] = 1;
  }
  diffuse.shade(ctx, paths, slots, rays, hits, shadowRays, history);
  misses.shade(ctx, paths, slots, rays, history);
}

void stageShadowResolve(const RayQueue& shadowRays, const PathSlotQueue& slots, PathQueue& paths, IndexRange range) {
  for (size_t k = range.begin; k < range.end; ++k) {
    // Occluded rays come back with tfar = -inf; disabled ones carry no contribution.
    if (!(shadowRays.tfar[k] >= 0)) continue;
    const uint32_t id = slots.path[k];
    addRadiance(paths, id, slots.neeAt(k));
  }
}

}  // namespace erpt
