// Three-component vectors of lanes, and the few pieces of math.h and surface.h that the vector
// kernels apply to them (the shade packet, the triangle surface kernel). Every formula is the
// scalar one written over batches, so a lane computes what the scalar code computes.
#pragma once

#include <xsimd/xsimd.hpp>

#include "kernels/lane_arch.h"

namespace erpt::lanes3 {

using batch = LaneBatch<float>;
using mask = batch::batch_bool_type;
using indices = LaneBatch<int32_t>;
static_assert(indices::size == batch::size, "one index lane per float lane");

struct V3 {
  batch x, y, z;
};
inline V3 operator+(const V3& a, const V3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 operator-(const V3& a, const V3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 operator-(const V3& a) { return {-a.x, -a.y, -a.z}; }
inline V3 operator*(const V3& a, const batch& s) { return {a.x * s, a.y * s, a.z * s}; }
inline V3 operator*(const V3& a, const V3& b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
inline V3 operator/(const V3& a, const batch& s) { return {a.x / s, a.y / s, a.z / s}; }
inline batch dot(const V3& a, const V3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V3 cross(const V3& a, const V3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline V3 select(const mask& m, const V3& a, const V3& b) {
  return {xsimd::select(m, a.x, b.x), xsimd::select(m, a.y, b.y), xsimd::select(m, a.z, b.z)};
}
inline mask isBlack(const V3& c) { return (c.x == batch(0.0f)) & (c.y == batch(0.0f)) & (c.z == batch(0.0f)); }

// Frame(n) of math.h (Duff et al.'s branchless basis), lane by lane.
struct LaneFrame {
  V3 s, t, n;
  explicit LaneFrame(const V3& normal) : n(normal) {
    const batch sign = xsimd::copysign(batch(1.0f), n.z);
    const batch a = batch(-1.0f) / (sign + n.z);
    const batch b = n.x * n.y * a;
    s = {batch(1.0f) + sign * n.x * n.x * a, sign * b, -sign * n.x};
    t = {b, sign + n.y * n.y * a, -n.y};
  }
  V3 toLocal(const V3& v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
  V3 toWorld(const V3& v) const { return s * v.x + t * v.y + n * v.z; }
};

// offsetOrigin of surface.h.
inline V3 offsetOrigin(const V3& p, const V3& ng, const V3& dir) {
  const batch scale =
      xsimd::max(xsimd::max(xsimd::abs(p.x), xsimd::abs(p.y)), xsimd::max(xsimd::abs(p.z), batch(1e-2f)));
  const batch eps = scale * 2e-5f;
  return p + ng * xsimd::select(dot(dir, ng) >= batch(0.0f), eps, -eps);
}

// shadowSegment of surface.h: the ray between two pushed surface points.
struct LaneShadowSegment {
  V3 origin, direction;
  batch tfar;
};
inline LaneShadowSegment shadowSegment(const V3& from, const V3& fromNg, const V3& to, const V3& toNg) {
  const V3 d = to - from;
  const V3 origin = offsetOrigin(from, fromNg, d), end = offsetOrigin(to, toNg, -d);
  const V3 span = end - origin;
  const batch length = xsimd::sqrt(dot(span, span));
  return {origin, span / length, length * (1 - 1e-4f)};
}

}  // namespace erpt::lanes3
