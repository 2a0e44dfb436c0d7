#include <limits>

#include "stages/stages.h"
#include "models/surface.h"
#include "tracer/tracer.h"

namespace erpt {

void stageGatherDirect(const StageContext& ctx, const RayQueue& shadowRays, const RayQueue& bsdfRays,
                       const HitQueue& bsdfHits, DirectSampleQueue& q, IndexRange range) {
  const Emitter* env = ctx.scene.environment();
  for (size_t i = range.begin; i < range.end; ++i) {
    Color total = q.radianceAt(i);
    // An occluded shadow ray has tfar = -inf; a disabled one carries zero contribution.
    if (shadowRays.tfar[i] >= 0) total += q.shadowAt(i);

    Color weight = q.bsdfAt(i);
    if (!isBlack(weight)) {
      Vec3 dir = bsdfRays.dirAt(i);
      float pdf = q.bsdfPdf[i];  // 0: a Dirac lobe, which next-event estimation cannot produce
      if (bsdfHits.geomID[i] == kRefusedRay) {  // the sample is invalid: the film drops and counts it
        total = Color(std::numeric_limits<float>::quiet_NaN());
      } else if (bsdfHits.geomID[i] == kNoHit) {
        if (env) {
          float lightPdf;
          const Color le = ctx.lights.environmentRadianceAndPdf(*env, dir, lightPdf);
          total += weight * le * emitterHitWeight(pdf, lightPdf);
        }
      } else {
        SurfacePoint lp = surfaceAt(ctx.scene, bsdfHits.primID[i], bsdfHits.u[i], bsdfHits.v[i]);
        Color le = ctx.lights.emitted(lp, -dir);
        if (!isBlack(le)) {
          float lightPdf = ctx.lights.pdfSolidAngle(lp, q.hitAt(i));
          total += weight * le * emitterHitWeight(pdf, lightPdf);
        }
      }
    }
    q.radianceSet(i, total);
  }
}

}  // namespace erpt
