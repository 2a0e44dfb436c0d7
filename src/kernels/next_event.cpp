#include <limits>

#include "kernels/kernels.h"

namespace erpt {

bool connectToLight(const LightSampler& lights, const SurfacePoint& sp, const Material& m, const SurfaceColors& colors,
                    Vec3 wiLocal, double uPick, float u1, float u2, LightConnection& out) {
  if (m.isPureSpecular()) return false;  // eval() would be 0 for every light direction
  LightSample ls;
  if (!lights.sample(sp.position, uPick, u1, u2, ls)) return false;
  Vec3 woLocal = sp.shading.toLocal(ls.direction);
  Color f = bsdfEval(m, colors, wiLocal, woLocal);
  if (isBlack(f)) return false;
  out.bsdfPdf = bsdfPdf(m, colors, wiLocal, woLocal);
  out.light = ls;
  if (ls.delta) {
    out.misWeight = 1;
    out.contribution = f * ls.radiance;
  } else {
    out.misWeight = powerHeuristic(ls.pdf, out.bsdfPdf);
    out.contribution = f * ls.radiance * (out.misWeight / ls.pdf);
  }
  if (ls.environment) {
    out.origin = offsetOrigin(sp.position, sp.geometricNormal, ls.direction);
    out.direction = ls.direction;
    out.tfar = std::numeric_limits<float>::infinity();
    return true;
  }
  const ShadowSegment segment =
      shadowSegment(sp.position, sp.geometricNormal, ls.position, ls.delta ? Vec3(0.0f) : ls.normal);
  out.origin = segment.origin;
  out.direction = segment.direction;
  out.tfar = segment.tfar;
  return true;
}

}  // namespace erpt
