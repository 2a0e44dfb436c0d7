#include "erpt/bsdf.h"
#include "erpt/rng.h"
#include "erpt/stages.h"
#include "erpt/surface.h"
#include "erpt/tracer.h"

namespace erpt {

namespace {
void setColor(float* r, float* g, float* b, size_t i, Color c) {
  r[i] = c.x;
  g[i] = c.y;
  b[i] = c.z;
}
}  // namespace

void stageShadeDirect(const StageContext& ctx, const RayQueue& cameraRays, const HitQueue& hits,
                      DirectSampleQueue& q, RayQueue& shadowRays, RayQueue& bsdfRays, IndexRange range) {
  const Emitter* env = ctx.scene.environment();
  for (size_t i = range.begin; i < range.end; ++i) {
    Color radiance(0.0f), shadow(0.0f), bsdfWeight(0.0f);
    q.bsdfPdf[i] = 0;
    disableRay(shadowRays, i);
    disableRay(bsdfRays, i);
    Vec3 dir{cameraRays.dirX[i], cameraRays.dirY[i], cameraRays.dirZ[i]};
    if (hits.geomID[i] == kNoHit) {
      if (env) radiance = env->radiance;
    } else {
      SurfacePoint sp = surfaceAt(ctx.scene.mesh, hits.primID[i], hits.u[i], hits.v[i]);
      radiance = ctx.lights.emitted(sp.triangle, -dir);
      q.hitX[i] = sp.position.x;
      q.hitY[i] = sp.position.y;
      q.hitZ[i] = sp.position.z;
      if (ctx.maxDepth != 1) {
        uint64_t key = sampleKey(ctx.seed, q.pixel[i], q.sample[i]);
        const Material& m = ctx.scene.materials[sp.material];
        SurfaceColors colors = ctx.scene.surfaceColors(sp.material, sp.u, sp.v);
        Vec3 wi = sp.shading.toLocal(-dir);

        // Next-event estimation, MIS-weighted against BSDF sampling.
        LightSample ls;
        if (ctx.lights.sample(sp.position, uniformFloat(key, kDimLightPick), uniformFloat(key, kDimLight1),
                              uniformFloat(key, kDimLight2), ls)) {
          Color f = bsdfEval(m, colors, wi, sp.shading.toLocal(ls.direction));
          if (!isBlack(f)) {
            float w = ls.delta ? 1.0f : powerHeuristic(ls.pdf, bsdfPdf(m, colors, wi, sp.shading.toLocal(ls.direction)));
            shadow = ls.delta ? f * ls.radiance : f * ls.radiance * (w / ls.pdf);
            Vec3 org = offsetOrigin(sp.position, sp.geometricNormal, ls.direction);
            float tfar = ls.environment ? std::numeric_limits<float>::infinity() : length(ls.position - org) * (1 - 1e-4f);
            setRay(shadowRays, i, org, ls.direction, 0.0f, tfar);
          }
        }

        // BSDF sampling: its ray may find an emitter (handled in stageGatherDirect).
        BsdfSample bs;
        if (bsdfSample(m, colors, wi, uniformFloat(key, kDimLobe), uniformFloat(key, kDimBsdf1),
                       uniformFloat(key, kDimBsdf2), bs) &&
            !isBlack(bs.weight)) {
          Vec3 wo = sp.shading.toWorld(bs.wo);
          bsdfWeight = bs.weight;
          q.bsdfPdf[i] = bs.delta ? 0.0f : bs.pdf;
          setRay(bsdfRays, i, offsetOrigin(sp.position, sp.geometricNormal, wo), wo, 0.0f,
                 std::numeric_limits<float>::infinity());
        }
      }
    }
    setColor(q.radianceR.data(), q.radianceG.data(), q.radianceB.data(), i, radiance);
    setColor(q.shadowR.data(), q.shadowG.data(), q.shadowB.data(), i, shadow);
    setColor(q.bsdfR.data(), q.bsdfG.data(), q.bsdfB.data(), i, bsdfWeight);
  }
}

}  // namespace erpt
