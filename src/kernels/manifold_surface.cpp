#include "kernels/manifold_surface.h"

#include <cmath>

namespace erpt {

namespace {
DVec3 d3(Vec3 v) { return {v.x, v.y, v.z}; }
double norm(DVec3 a) { return std::sqrt(dot(a, a)); }
}  // namespace

ManifoldVertex manifoldTriangleVertex(const TriangleSoup& mesh, uint32_t tri, double b1, double b2) {
  const uint32_t i0 = mesh.v0[tri], i1 = mesh.v1[tri], i2 = mesh.v2[tri];
  const DVec3 p0 = d3(mesh.position(i0)), p1 = d3(mesh.position(i1)), p2 = d3(mesh.position(i2));
  const double w1 = b1, w2 = b2, w0 = 1 - w1 - w2;
  ManifoldVertex v;
  v.p = p0 * w0 + p1 * w1 + p2 * w2;
  v.dpdu = p1 - p0;
  v.dpdv = p2 - p0;
  v.surface = uint32_t(mesh.shape[tri]);
  if (!mesh.smooth[tri]) {  // a flat triangle: its face normal, which does not turn
    const DVec3 face = cross(v.dpdu, v.dpdv);
    v.n = face * (1.0 / norm(face));
    return v;
  }
  // N(b1, b2) = w0 n0 + w1 n1 + w2 n2 turns by n1 - n0 and n2 - n0 per unit of b1 and b2; over
  // |N|, so that normalize(n + u dndu + v dndv) is N's direction at (b1 + u, b2 + v).
  const DVec3 n0 = d3(mesh.normal(i0)), n1 = d3(mesh.normal(i1)), n2 = d3(mesh.normal(i2));
  const DVec3 interpolated = n0 * w0 + n1 * w1 + n2 * w2;
  const double length = norm(interpolated);
  v.n = interpolated * (1.0 / length);
  v.dndu = (n1 - n0) * (1.0 / length);
  v.dndv = (n2 - n0) * (1.0 / length);
  return v;
}

ManifoldVertex manifoldSphereVertex(const SphereSet& spheres, uint32_t i, DVec3 p) {
  const DVec3 c = d3(spheres.center(i));
  const double r = spheres.radius[i];
  DVec3 out = p - c;
  out = out * (1.0 / norm(out));
  const double side = spheres.flipped[i] ? -1.0 : 1.0;
  ManifoldVertex v;
  v.p = c + out * r;
  v.n = out * side;
  const DVec3 helper = std::abs(out.x) < 0.9 ? DVec3{1, 0, 0} : DVec3{0, 1, 0};
  const DVec3 s = cross(helper, out);
  v.dpdu = s * (1.0 / norm(s));
  v.dpdv = cross(out, v.dpdu);
  // n = side (p - c) / r: it turns by side dp / r.
  v.dndu = v.dpdu * (side / r);
  v.dndv = v.dpdv * (side / r);
  v.surface = uint32_t(spheres.shape[i]);
  return v;
}

}  // namespace erpt
