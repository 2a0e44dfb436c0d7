#include "untraceable_rays.h"

#include <cfloat>
#include <cmath>

namespace erpt {

namespace {
// Written without branches or std::isfinite so that the scan over a whole batch vectorizes;
// NaN fails every comparison.
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
}  // namespace

bool isTraceable(const RayQueue& rays, size_t i) { return wellFormed(rays, i) | disabled(rays, i); }

size_t refuseUntraceableRays(RayQueue& rays, IndexRange range, std::vector<uint32_t>& refused) {
  bool all = true;
  for (size_t i = range.begin; i < range.end; ++i) all &= wellFormed(rays, i);
  if (all) return 0;  // the common case: one pass, nothing written
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
