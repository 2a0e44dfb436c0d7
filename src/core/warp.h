// Warps from the unit square to sampling domains, each with its density.
#pragma once

#include "erpt/math.h"

namespace erpt {

// Concentric (Shirley-Chiu) map: low distortion, so stratification survives the warp.
inline void squareToDisk(float u1, float u2, float& x, float& y) {
  float a = 2 * u1 - 1, b = 2 * u2 - 1;
  if (a == 0 && b == 0) {
    x = y = 0;
    return;
  }
  float r, phi;
  if (a * a > b * b) {
    r = a;
    phi = (kPi / 4) * (b / a);
  } else {
    r = b;
    phi = kPi / 2 - (kPi / 4) * (a / b);
  }
  x = r * std::cos(phi);
  y = r * std::sin(phi);
}

inline Vec3 squareToCosineHemisphere(float u1, float u2) {
  float x, y;
  squareToDisk(u1, u2, x, y);
  return {x, y, std::sqrt(std::max(0.0f, 1 - x * x - y * y))};
}
inline float cosineHemispherePdf(Vec3 w) { return w.z > 0 ? w.z * kInvPi : 0.0f; }

inline Vec3 squareToUniformSphere(float u1, float u2) {
  float z = 1 - 2 * u1, r = std::sqrt(std::max(0.0f, 1 - z * z)), phi = 2 * kPi * u2;
  return {r * std::cos(phi), r * std::sin(phi), z};
}
constexpr float kUniformSpherePdf = 0.25f * kInvPi;

// Uniform point on a triangle as barycentrics (b1, b2) (Heitz 2019's low-distortion map).
inline void squareToTriangle(float u1, float u2, float& b1, float& b2) {
  if (u1 < u2) {
    b1 = u1 / 2;
    b2 = u2 - b1;
  } else {
    b2 = u2 / 2;
    b1 = u1 - b2;
  }
}

}  // namespace erpt
