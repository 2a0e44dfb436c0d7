#include <limits>

#include "models/bsdf.h"
#include "core/rng.h"
#include "stages/stages.h"
#include "models/surface.h"
#include "tracer/tracer.h"

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
    Vec3 dir = cameraRays.dirAt(i);
    if (hits.geomID[i] == kRefusedRay) {  // the sample is invalid: the film drops and counts it
      radiance = Color(std::numeric_limits<float>::quiet_NaN());
    } else if (hits.geomID[i] == kNoHit) {
      if (env) radiance = env->environmentRadiance(dir);
    } else {
      SurfacePoint sp = surfaceAt(ctx.scene, hits.primID[i], hits.u[i], hits.v[i]);
      radiance = ctx.lights.emitted(sp, -dir);
      q.hitSet(i, sp.position);
      if (ctx.maxDepth != 1) {
        uint64_t key = sampleKey(ctx.seed, q.pixel[i], q.sample[i]);
        const Material& m = ctx.scene.materials[sp.material];
        SurfaceColors colors = ctx.scene.surfaceColors(sp.material, sp.u, sp.v);
        Vec3 wi = sp.shading.toLocal(-dir);

        // Next-event estimation, MIS-weighted against BSDF sampling.
        LightConnection lc;
        if (connectToLight(ctx.lights, sp, m, colors, wi, uniformDouble(key, bounceDim(1, kLightPick)),
                           uniformFloat(key, bounceDim(1, kLight1)), uniformFloat(key, bounceDim(1, kLight2)), lc)) {
          shadow = lc.contribution;
          setRay(shadowRays, i, lc.origin, lc.direction, 0.0f, lc.tfar);
        }

        // BSDF sampling: its ray may find an emitter (handled in stageGatherDirect).
        BsdfSample bs;
        if (bsdfSample(m, colors, wi, uniformFloat(key, bounceDim(1, kLobe)), uniformFloat(key, bounceDim(1, kBsdf1)),
                       uniformFloat(key, bounceDim(1, kBsdf2)), bs) &&
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
