// The local geometry at a ray hit, reconstructed from the scene's SoA mesh columns.
#pragma once

#include "erpt/scene.h"

namespace erpt {

struct SurfacePoint {
  Vec3 position;
  Vec3 geometricNormal;  // unit, from the triangle's winding (emission and flip_normals follow it)
  Frame shading;         // around the interpolated shading normal (or the geometric one)
  float u = 0, v = 0;    // texture coordinates
  uint32_t triangle = 0;
  int material = 0;
};

// b1, b2: barycentric coordinates of the triangle's second and third vertex (Embree's u, v).
inline SurfacePoint surfaceAt(const TriangleSoup& m, uint32_t tri, float b1, float b2) {
  SurfacePoint s;
  uint32_t i0 = m.v0[tri], i1 = m.v1[tri], i2 = m.v2[tri];
  float b0 = 1 - b1 - b2;
  s.position = m.position(i0) * b0 + m.position(i1) * b1 + m.position(i2) * b2;
  s.geometricNormal = normalize(m.faceNormal(tri));
  Vec3 n = s.geometricNormal;
  if (m.smooth[tri]) {
    Vec3 ns = m.normal(i0) * b0 + m.normal(i1) * b1 + m.normal(i2) * b2;
    float len = length(ns);
    if (len > 0) n = ns / len;
  }
  s.shading = Frame(n);
  s.u = m.u[i0] * b0 + m.u[i1] * b1 + m.u[i2] * b2;
  s.v = m.v[i0] * b0 + m.v[i1] * b1 + m.v[i2] * b2;
  s.triangle = tri;
  s.material = m.material[tri];
  return s;
}

// Origin for a ray leaving surface point p towards `dir`: pushed off the surface along the
// geometric normal by an amount that grows with the coordinates' magnitude (float spacing),
// so it works for both tiny and huge scenes.
inline Vec3 offsetOrigin(Vec3 p, Vec3 geometricNormal, Vec3 dir) {
  float scale = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z), 1e-2f});
  float eps = scale * 2e-5f;
  return p + geometricNormal * (dot(dir, geometricNormal) >= 0 ? eps : -eps);
}

}  // namespace erpt
