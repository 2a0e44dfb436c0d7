#include "kernels/surface_lanes.h"

#include "kernels/lane_gather.h"

namespace erpt {

using namespace lanes3;

LaneTriangleHit triangleHitLanes(const TriangleSoup& mesh, const indices& triangle, const batch& b1, const batch& b2,
                                 const mask& smooth) {
  auto gather3 = [&](const auto& x, const auto& y, const auto& z, const indices& at) {
    return V3{gatherLanes(x.data(), at), gatherLanes(y.data(), at), gatherLanes(z.data(), at)};
  };
  const batch b0 = 1.0f - b1 - b2;
  const indices i0 = gatherLanes(reinterpret_cast<const int32_t*>(mesh.v0.data()), triangle);
  const indices i1 = gatherLanes(reinterpret_cast<const int32_t*>(mesh.v1.data()), triangle);
  const indices i2 = gatherLanes(reinterpret_cast<const int32_t*>(mesh.v2.data()), triangle);
  const V3 p0 = gather3(mesh.px, mesh.py, mesh.pz, i0), p1 = gather3(mesh.px, mesh.py, mesh.pz, i1),
           p2 = gather3(mesh.px, mesh.py, mesh.pz, i2);
  LaneTriangleHit hit;
  hit.position = p0 * b0 + p1 * b1 + p2 * b2;
  const V3 face = cross(p1 - p0, p2 - p0);
  hit.ng = face / xsimd::sqrt(dot(face, face));
  hit.shading = hit.ng;
  if (mesh.nx.size() != mesh.vertexCount() || !xsimd::any(smooth)) return hit;  // the loader gives every vertex one
  const V3 interpolated = gather3(mesh.nx, mesh.ny, mesh.nz, i0) * b0 + gather3(mesh.nx, mesh.ny, mesh.nz, i1) * b1 +
                          gather3(mesh.nx, mesh.ny, mesh.nz, i2) * b2;
  const batch length = xsimd::sqrt(dot(interpolated, interpolated));
  hit.shading = select(smooth & (length > batch(0.0f)), interpolated / length, hit.ng);
  return hit;
}

V3 cosineHemisphereLanes(const batch& u1, const batch& u2) {
  const batch a = 2.0f * u1 - 1.0f, b = 2.0f * u2 - 1.0f;
  const mask wide = a * a > b * b;
  const batch r = xsimd::select(wide, a, b);
  const batch ratio = xsimd::select(wide, b, a) / r;  // 0/0 at the centre, replaced below
  const batch quarter(kPi / 4);
  const batch phi = xsimd::select(wide, quarter * ratio, batch(kPi / 2) - quarter * ratio);
  const auto sc = xsimd::sincos(phi);
  const mask centre = (a == batch(0.0f)) & (b == batch(0.0f));
  const batch x = xsimd::select(centre, batch(0.0f), r * sc.second);
  const batch y = xsimd::select(centre, batch(0.0f), r * sc.first);
  return {x, y, xsimd::sqrt(xsimd::max(batch(0.0f), 1.0f - x * x - y * y))};
}

}  // namespace erpt
