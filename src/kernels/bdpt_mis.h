// Multiple importance sampling over BDPT's strategies (Veach's thesis, ch. 10; docs/bdpt.md).
//
// A path x_0 .. x_k (x_0 on the camera, x_k on a light) can be made by k + 1 strategies:
// s = 0 .. k light vertices and t = k + 1 - s camera vertices (t >= 1: the camera is never hit).
// Each strategy samples the path with a density p_s(x): the product over the vertices of how
// each was sampled, from the camera side (x_i for i < t) or the light side (i >= t).
// The densities per vertex, in area measure (solid angle for a vertex at infinity):
//   cameraDensity[i]: x_i sampled from x_{i-1} (the camera's film density for x_1, BSDF sampling
//                     at x_{i-1} arriving from x_{i-2} for i >= 2); cameraDensity[0] the lens;
//   lightDensity[i]:  x_i sampled from x_{i+1} (emission for x_{k-1}, BSDF sampling at x_{i+1}
//                     arriving from x_{i+2} below), lightDensity[k] the light vertex's own
//                     emission density;
//   nextEventDensity: x_k chosen by next-event estimation from x_{k-1} (strategy s = 1, which
//                     picks light points differently: the cone of a sphere).
// A Dirac lobe's direction counts as its lobe probability, converted to area like a density;
// the strategies that would connect through such a vertex are impossible. The weight is the
// power heuristic, w_s = p_s^2 / sum over possible strategies p_j^2; the weights of one path
// sum to 1 whatever densities are used, which keeps the estimate unbiased.
#pragma once

#include <cstdint>

namespace erpt {

struct BdptMisPath {
  int k = 0;                          // segments
  const float* cameraDensity = nullptr;  // k + 1 entries
  const float* lightDensity = nullptr;   // k + 1 entries
  const uint8_t* specular = nullptr;     // k + 1 flags: a Dirac lobe was (or would be) taken at x_i
  float nextEventDensity = 0;
  bool lightHittable = true;  // s = 0 possible: an area or environment light (not a point or directional light)
  bool lightSeenByLightTracing = true;  // k = 1, s = 1 (the light point connected to the camera): finite area lights
};

// Whether strategy s can make the path.
bool bdptStrategyPossible(const BdptMisPath& path, int s);
// The power-heuristic weight of strategy s (which must be possible and have made the path:
// its own densities are positive).
float bdptMisWeight(const BdptMisPath& path, int s);

}  // namespace erpt
