// Per-sample light transport kernels shared by the integrators' stages: pure functions of
// the scene, with no queues and no ray tracing.
#pragma once

#include "models/bsdf.h"
#include "models/light_sampler.h"
#include "models/surface.h"

namespace erpt {

// Power heuristic (exponent 2) weight of a strategy with pdf a against one with pdf b.
inline float powerHeuristic(float a, float b) {
  a *= a;
  b *= b;
  return a + b > 0 ? a / (a + b) : 0.0f;
}

// MIS weight of emission reached by BSDF sampling with solid-angle pdf `bsdfPdf`, against
// next-event estimation that would have picked the same point with `lightPdf`. A Dirac lobe
// (or the camera ray) has bsdfPdf = 0: next-event estimation cannot produce that path.
inline float emitterHitWeight(float bsdfPdf, float lightPdf) {
  return bsdfPdf > 0 ? powerHeuristic(bsdfPdf, lightPdf) : 1.0f;
}

// A next-event connection: the shadow ray to trace and what it carries if unoccluded.
struct LightConnection {
  Vec3 origin, direction;
  float tfar;
  Color contribution;  // f * cos * Le * MIS weight / pdf (without the path throughput)
  float misWeight;     // the MIS weight included in `contribution`
  float bsdfPdf;       // BSDF pdf of `direction` (what BSDF sampling would have used)
  LightSample light;   // the light point
};

// Next-event estimation at a surface point; false when the sample carries nothing.
bool connectToLight(const LightSampler& lights, const SurfacePoint& sp, const Material& m, const SurfaceColors& colors,
                    Vec3 wiLocal, double uPick, float u1, float u2, LightConnection& out);

}  // namespace erpt
