// The one Embree-facing type. Rays are traced in streams (rtcIntersectNp / rtcOccludedNp)
// straight from the SoA ray columns of a RayQueue; only camera rays are flagged coherent
// (flagging incoherent rays coherent costs ~3.5x on this hardware, see
// shared/measurements/embree-limits.md).
#pragma once

#include <memory>

#include "core/queues.h"
#include "tracer/ray_queues.h"
#include "erpt/scene.h"

namespace erpt {

enum class RayCoherence { Coherent, Incoherent };

// HitQueue::geomID of a ray that hit nothing (Embree's RTC_INVALID_GEOMETRY_ID).
constexpr unsigned kNoHit = 0xffffffffu;
// HitQueue::geomID of a ray the tracer refused to trace: a non-finite origin or direction, a
// zero direction or a NaN interval (src/tracer/untraceable_rays.h). Such a ray comes from a
// defect upstream; stages drop the sample it belongs to (the path tracer counts it invalid)
// or reject the proposal, and never read the hit.
constexpr unsigned kRefusedRay = 0xfffffffeu;

class Tracer {
 public:
  explicit Tracer(const Scene& scene);
  ~Tracer();
  Tracer(const Tracer&) = delete;
  Tracer& operator=(const Tracer&) = delete;

  // Closest hits for rays[range]; writes hits[range] and shortens rays.tfar to the hit.
  void intersect(RayQueue& rays, HitQueue& hits, IndexRange range, RayCoherence coherence) const;
  // Any-hit test for rays[range]: occluded rays get tfar = -inf. Refused rays count as occluded.
  void occluded(RayQueue& rays, IndexRange range) const;
  // Rays refused by intersect() and occluded() so far, over all threads.
  uint64_t refusedRays() const;

  // The same, one ray at a time (rtcIntersect1 / rtcOccluded1): only for A/B benchmarks
  // against the stream calls, never in the render path.
  void intersectOneByOne(RayQueue& rays, HitQueue& hits, IndexRange range) const;
  void occludedOneByOne(RayQueue& rays, IndexRange range) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Sizes a ray queue for n rays and fills the columns Embree reads but we never change
// (time 0, all mask bits, id, no flags), so stages write only origin, direction and interval.
inline void prepareRays(RayQueue& q, size_t n) {
  q.resize(n);
  for (size_t i = 0; i < n; ++i) {
    q.time[i] = 0;
    q.mask[i] = 0xffffffffu;
    q.id[i] = unsigned(i);
    q.flags[i] = 0;
    q.tnear[i] = 1.0f;  // inactive until a stage sets the ray
    q.tfar[i] = 0.0f;
  }
}

// Aims ray i of a queue made by prepareRays (its mask, id and flags stay as prepared).
inline void setRay(RayQueue& q, size_t i, Vec3 org, Vec3 dir, float tnear, float tfar) {
  q.orgSet(i, org);
  q.dirSet(i, dir);
  q.tnear[i] = tnear;
  q.tfar[i] = tfar;
}

// Marks ray i as inactive: Embree skips rays whose interval is empty.
inline void disableRay(RayQueue& q, size_t i) {
  q.tnear[i] = 1.0f;
  q.tfar[i] = 0.0f;
}

}  // namespace erpt
