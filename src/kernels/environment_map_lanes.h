// An environment map's importance sampling and lookup in vector lanes: what
// EnvironmentMap::sample and EnvironmentMap::evalAndPdf compute, eight directions at a time,
// for the path tracer's diffuse shade packet. Under an environment map the scalar shading spent
// about 40% of a render in these two (two CDF searches, a sine and cosine pair, an arc tangent
// and an arc cosine, two bilinear lookups per light sample), one direction at a time.
//
// The CDF searches pick the same pixel as the scalar code for the same numbers (the same
// comparisons in float); the trigonometry is xsimd's, so directions and densities agree with
// the scalar ones up to rounding.
#pragma once

#include "erpt/environment_map.h"
#include "kernels/lane_vec3.h"

namespace erpt {

struct LaneEnvironmentSample {
  lanes3::V3 direction;  // unit, in the world
  lanes3::V3 radiance;   // arriving from `direction`
  lanes3::batch pdf;     // the map's solid-angle density of `direction`
  lanes3::mask ok;       // pdf > 0 (sample() returned true)
};

// EnvironmentMap::sample(u1, u2, ...) with its radiance, lane by lane.
LaneEnvironmentSample sampleEnvironmentLanes(const EnvironmentMap::Tables& map, const lanes3::batch& u1,
                                             const lanes3::batch& u2);

// EnvironmentMap::evalAndPdf(direction, pdf), lane by lane: the radiance, and the density in pdf.
lanes3::V3 environmentEvalAndPdfLanes(const EnvironmentMap::Tables& map, const lanes3::V3& direction,
                                      lanes3::batch& pdf);

}  // namespace erpt
