// Shared set-up for the benchmarks: scenes and reproducible ray sets.
#pragma once

#include <string>

#include "core/queues.h"
#include "tracer/ray_queues.h"
#include "erpt/scene.h"

namespace erpt::bench {

Scene loadCornellBox();  // ../shared/scenes/cornell-box/scene.xml
Scene loadDefaultScene();

enum class RaySet { Primary, Diffuse, Shadow };
// `n` rays of a kind, as in shared/measurements/embree-limits.md: primary = one jittered
// camera ray per pixel in 16x16 tiles; diffuse = cosine-distributed rays from surface points
// chosen by area, in random order; shadow = segments between random surface points.
RayQueue makeRays(const Scene& scene, RaySet kind, size_t n, uint64_t seed = 1);

}  // namespace erpt::bench
