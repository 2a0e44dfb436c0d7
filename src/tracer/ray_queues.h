// The tracer's queues, declared once as queue_fields.h declares the others (F scalar, V Vec3,
// C Color columns; soa.h builds the structs): rays and closest hits as Embree's stream API
// reads and writes them.
#pragma once

#include "core/soa.h"

// Rays as Embree's stream API reads them (RTCRayNp): one column per component.
#define ERPT_RAY_FIELDS(F, V, C)                                                                    \
  V(org, "origin")                                                                                  \
  F(float, tnear, {}, "start of the valid interval")                                                \
  V(dir, "direction (need not be normalized)")                                                      \
  F(float, time, {}, "motion blur time (unused, 0)")                                                \
  F(float, tfar, {}, "end of the interval; the hit distance after intersect, -inf if occluded")     \
  F(unsigned, mask, {}, "Embree ray mask")                                                          \
  F(unsigned, id, {}, "Embree ray id")                                                              \
  F(unsigned, flags, {}, "Embree ray flags")

// Closest-hit results (RTCHitNp).
#define ERPT_HIT_FIELDS(F, V, C)                                                                    \
  V(ng, "Embree's unnormalized geometric normal")                                                   \
  F(float, u, {}, "triangle: barycentric of vertex 1; sphere: u")                                   \
  F(float, v, {}, "triangle: barycentric of vertex 2; sphere: v")                                   \
  F(unsigned, primID, {}, "primitive id (scene.h: triangles, then spheres)")                        \
  F(unsigned, geomID, {}, "RTC_INVALID_GEOMETRY_ID on a miss")                                      \
  F(unsigned, instID, {}, "Embree instance geometry of the hit (tracer-internal)")

namespace erpt {

ERPT_SOA_STRUCT(RayQueue, ERPT_RAY_FIELDS)
ERPT_SOA_STRUCT(HitQueue, ERPT_HIT_FIELDS)

}  // namespace erpt
