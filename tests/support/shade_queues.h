// The queues the path tracer's shade stage reads and writes, for the stage tests: n slots,
// slot k carrying path k.
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/queues.h"
#include "tracer/ray_queues.h"

namespace erpt::test {

struct ShadeQueues {
  PathQueue paths;
  PathSlotQueue slots;
  RayQueue rays, shadowRays;
  HitQueue hits;

  explicit ShadeQueues(size_t n);
  // Path k as sample k / pixels of pixel k % pixels of `seed`, its ray leaving `origin` (the
  // path's previous vertex) along `direction`.
  void startSlot(size_t k, uint64_t seed, uint32_t pixels, Vec3 origin, Vec3 direction);
};

}  // namespace erpt::test
