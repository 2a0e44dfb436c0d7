// The one Embree-facing type. Rays are traced in streams (rtcIntersectNp / rtcOccludedNp)
// straight from the SoA ray columns of a RayQueue; only camera rays are flagged coherent
// (flagging incoherent rays coherent costs ~3.5x on this hardware, see
// shared/measurements/embree-limits.md).
#pragma once

#include <memory>

#include "erpt/queues.h"
#include "erpt/scene.h"

namespace erpt {

enum class RayCoherence { Coherent, Incoherent };

// HitQueue::geomID of a ray that hit nothing (Embree's RTC_INVALID_GEOMETRY_ID).
constexpr unsigned kNoHit = 0xffffffffu;

class Tracer {
 public:
  explicit Tracer(const Scene& scene);
  ~Tracer();
  Tracer(const Tracer&) = delete;
  Tracer& operator=(const Tracer&) = delete;

  // Closest hits for rays[range]; writes hits[range] and shortens rays.tfar to the hit.
  void intersect(RayQueue& rays, HitQueue& hits, IndexRange range, RayCoherence coherence) const;
  // Any-hit test for rays[range]: occluded rays get tfar = -inf.
  void occluded(RayQueue& rays, IndexRange range) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Fills ray i of a queue (tnear 0, mask all, flags 0).
inline void setRay(RayQueue& q, size_t i, Vec3 org, Vec3 dir, float tnear, float tfar) {
  q.orgX[i] = org.x;
  q.orgY[i] = org.y;
  q.orgZ[i] = org.z;
  q.dirX[i] = dir.x;
  q.dirY[i] = dir.y;
  q.dirZ[i] = dir.z;
  q.tnear[i] = tnear;
  q.tfar[i] = tfar;
  q.time[i] = 0;
  q.mask[i] = 0xffffffffu;
  q.id[i] = unsigned(i);
  q.flags[i] = 0;
}

// Marks ray i as inactive: Embree skips rays whose interval is empty.
inline void disableRay(RayQueue& q, size_t i) { setRay(q, i, Vec3(0.0f), Vec3(0, 0, 1), 1.0f, 0.0f); }

}  // namespace erpt
