#include "untraceable_rays.h"

#include <cfloat>
#include <cmath>

#include <xsimd/xsimd.hpp>

#include "kernels/lane_arch.h"

namespace erpt {

namespace {
using batch = LaneBatch<float>;

// NaN fails every comparison, so !(|v| <= FLT_MAX) catches NaN and both infinities.
inline bool finite(float v) { return std::abs(v) <= FLT_MAX; }

// Finite origin, finite non-zero direction, finite tnear >= 0 and a tfar that is not NaN
// (+inf is unbounded; -inf marks an occluded ray).
inline bool wellFormed(const RayQueue& rays, size_t i) {
  const bool origin = finite(rays.orgX[i]) & finite(rays.orgY[i]) & finite(rays.orgZ[i]);
  const bool direction = finite(rays.dirX[i]) & finite(rays.dirY[i]) & finite(rays.dirZ[i]) &
                         ((rays.dirX[i] != 0) | (rays.dirY[i] != 0) | (rays.dirZ[i] != 0));
  const bool interval = finite(rays.tnear[i]) & (rays.tnear[i] >= 0) & !std::isnan(rays.tfar[i]);
  return origin & direction & interval;
}

inline bool disabled(const RayQueue& rays, size_t i) { return rays.tnear[i] > rays.tfar[i]; }

// Whether every ray of [begin, end) is well formed: the common case, tested a SIMD batch of
// rays at a time over the columns (the scalar test per ray cost ~4% of a path-traced render).
bool allWellFormed(const RayQueue& rays, size_t begin, size_t end) {
  const batch maxFinite(FLT_MAX), zero(0.0f);
  auto column = [](const auto& c, size_t i) { return batch::load_unaligned(c.data() + i); };
  size_t i = begin;
  for (; i + batch::size <= end; i += batch::size) {
    const batch dx = column(rays.dirX, i), dy = column(rays.dirY, i), dz = column(rays.dirZ, i);
    const batch tnear = column(rays.tnear, i), tfar = column(rays.tfar, i);
    const batch largest = xsimd::max(xsimd::max(xsimd::abs(column(rays.orgX, i)), xsimd::abs(column(rays.orgY, i))),
                                     xsimd::max(xsimd::abs(column(rays.orgZ, i)), xsimd::abs(tnear)));
    const batch direction = xsimd::max(xsimd::max(xsimd::abs(dx), xsimd::abs(dy)), xsimd::abs(dz));
    // xsimd::max may drop a NaN operand; the NaN checks below catch what it drops.
    const auto good = (largest <= maxFinite) & (direction <= maxFinite) & (direction > zero) & (tnear >= zero) &
                      (tfar == tfar) & (dx == dx) & (dy == dy) & (dz == dz) &
                      (column(rays.orgX, i) == column(rays.orgX, i)) & (column(rays.orgY, i) == column(rays.orgY, i)) &
                      (column(rays.orgZ, i) == column(rays.orgZ, i)) & (tnear == tnear);
    if (!xsimd::all(good)) return false;
  }
  for (; i < end; ++i)
    if (!wellFormed(rays, i)) return false;
  return true;
}
}  // namespace

bool isTraceable(const RayQueue& rays, size_t i) { return wellFormed(rays, i) | disabled(rays, i); }

size_t refuseUntraceableRays(RayQueue& rays, IndexRange range, std::vector<uint32_t>& refused) {
  if (allWellFormed(rays, range.begin, range.end)) return 0;  // nothing written
  size_t count = 0;
  for (size_t i = range.begin; i < range.end; ++i) {
    if (wellFormed(rays, i)) continue;
    if (!disabled(rays, i)) {
      refused.push_back(uint32_t(i));
      ++count;
    }
    // Disabled (an empty interval) and given harmless columns: Embree reads the columns of
    // inactive rays too, so a disabled ray with stale non-finite data is cleaned as well.
    rays.orgSet(i, Vec3(0.0f));
    rays.dirSet(i, Vec3(0.0f, 0.0f, 1.0f));
    rays.tnear[i] = 1.0f;
    rays.tfar[i] = 0.0f;
  }
  return count;
}

}  // namespace erpt
