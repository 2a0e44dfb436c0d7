// Path tracer surface stage: emission (MIS-weighted), next-event estimation, BSDF sampling
// and Russian roulette for every live slot.
#include "erpt/rng.h"
#include "erpt/stages.h"
#include "erpt/tracer.h"

namespace erpt {

namespace {

Color throughputOf(const PathQueue& p, uint32_t id) { return {p.throughputR[id], p.throughputG[id], p.throughputB[id]}; }

void addRadiance(PathQueue& p, uint32_t id, Color c) {
  p.radianceR[id] += c.x;
  p.radianceG[id] += c.y;
  p.radianceB[id] += c.z;
}

}  // namespace

void stageShadePath(const StageContext& ctx, PathQueue& paths, PathSlotQueue& slots, RayQueue& rays,
                    const HitQueue& hits, RayQueue& shadowRays, IndexRange range) {
  const Emitter* env = ctx.scene.environment();
  for (size_t k = range.begin; k < range.end; ++k) {
    const uint32_t id = slots.path[k];
    slots.alive[k] = 0;
    slots.neeR[k] = slots.neeG[k] = slots.neeB[k] = 0;
    disableRay(shadowRays, k);
    const uint32_t depth = paths.depth[id];  // segments so far, including the ray just traced
    const Color throughput = throughputOf(paths, id);
    const Vec3 dir{rays.dirX[k], rays.dirY[k], rays.dirZ[k]};
    const Vec3 prev{paths.prevX[id], paths.prevY[id], paths.prevZ[id]};
    const float prevPdf = paths.prevPdf[id];

    if (hits.geomID[k] == kNoHit) {
      if (env) addRadiance(paths, id, throughput * env->radiance * emitterHitWeight(prevPdf, ctx.lights.pdfEnvironment()));
      continue;
    }
    const SurfacePoint sp = surfaceAt(ctx.scene.mesh, hits.primID[k], hits.u[k], hits.v[k]);
    const Color le = ctx.lights.emitted(sp.triangle, -dir);
    if (!isBlack(le)) {
      float lightPdf = prevPdf > 0 ? ctx.lights.pdfTriangle(sp.triangle, prev, sp.position, sp.geometricNormal) : 0.0f;
      addRadiance(paths, id, throughput * le * emitterHitWeight(prevPdf, lightPdf));
    }
    // A path of maxDepth segments can grow no further (-1: unbounded).
    if (ctx.maxDepth >= 0 && depth >= uint32_t(ctx.maxDepth)) continue;

    const uint64_t key = sampleKey(ctx.seed, paths.pixel[id], paths.sample[id]);
    const Material& m = ctx.scene.materials[sp.material];
    const SurfaceColors colors = ctx.scene.surfaceColors(sp.material, sp.u, sp.v);
    const Vec3 wi = sp.shading.toLocal(-dir);

    LightConnection lc;
    if (connectToLight(ctx.lights, sp, m, colors, wi, uniformFloat(key, bounceDim(depth, kLightPick)),
                       uniformFloat(key, bounceDim(depth, kLight1)), uniformFloat(key, bounceDim(depth, kLight2)), lc)) {
      Color c = throughput * lc.contribution;
      slots.neeR[k] = c.x;
      slots.neeG[k] = c.y;
      slots.neeB[k] = c.z;
      setRay(shadowRays, k, lc.origin, lc.direction, 0.0f, lc.tfar);
    }

    BsdfSample bs;
    if (!bsdfSample(m, colors, wi, uniformFloat(key, bounceDim(depth, kLobe)), uniformFloat(key, bounceDim(depth, kBsdf1)),
                    uniformFloat(key, bounceDim(depth, kBsdf2)), bs) ||
        isBlack(bs.weight))
      continue;
    Color next = throughput * bs.weight;
    if (int(depth) >= ctx.rrDepth) {
      // Russian roulette: survive with probability q, reweight by 1/q (unbiased).
      float q = std::min(0.95f, maxComponent(next));
      if (!(uniformFloat(key, bounceDim(depth, kRoulette)) < q)) continue;
      next = next / q;
    }
    paths.throughputR[id] = next.x;
    paths.throughputG[id] = next.y;
    paths.throughputB[id] = next.z;
    paths.prevPdf[id] = bs.delta ? 0.0f : bs.pdf;
    paths.prevX[id] = sp.position.x;
    paths.prevY[id] = sp.position.y;
    paths.prevZ[id] = sp.position.z;
    paths.depth[id] = depth + 1;
    const Vec3 wo = sp.shading.toWorld(bs.wo);
    setRay(rays, k, offsetOrigin(sp.position, sp.geometricNormal, wo), wo, 0.0f, std::numeric_limits<float>::infinity());
    slots.alive[k] = 1;
  }
}

void stageShadowResolve(const RayQueue& shadowRays, const PathSlotQueue& slots, PathQueue& paths, IndexRange range) {
  for (size_t k = range.begin; k < range.end; ++k) {
    // Occluded rays come back with tfar = -inf; disabled ones carry no contribution.
    if (!(shadowRays.tfar[k] >= 0)) continue;
    const uint32_t id = slots.path[k];
    paths.radianceR[id] += slots.neeR[k];
    paths.radianceG[id] += slots.neeG[k];
    paths.radianceB[id] += slots.neeB[k];
  }
}

}  // namespace erpt
