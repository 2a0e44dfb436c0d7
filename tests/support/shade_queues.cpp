#include "support/shade_queues.h"

#include <limits>

#include "core/rng.h"
#include "stages/stages.h"
#include "tracer/tracer.h"

namespace erpt::test {

ShadeQueues::ShadeQueues(size_t n) {
  paths.resize(n);
  slots.resize(n);
  prepareRays(rays, n);
  prepareRays(shadowRays, n);
  hits.resize(n);
}

void ShadeQueues::startSlot(size_t k, uint64_t seed, uint32_t pixels, Vec3 origin, Vec3 direction) {
  const uint32_t pixel = uint32_t(k % pixels), sample = uint32_t(k / pixels);
  startPath(paths, uint32_t(k), sampleKey(seed, pixel, sample), pixel, sample);
  paths.prevSet(k, origin);
  slots.path[k] = uint32_t(k);
  setRay(rays, k, origin, direction, 0.0f, std::numeric_limits<float>::infinity());
}

}  // namespace erpt::test
