// Shared set-up for the benchmarks: scenes and reproducible ray sets.
#pragma once

#include <benchmark/benchmark.h>

#include <string>

#include "core/queues.h"
#include "tracer/ray_queues.h"
#include "erpt/render.h"
#include "erpt/scene.h"

namespace erpt::bench {

Scene loadCornellBox();  // ../shared/scenes/cornell-box/scene.xml
Scene loadDefaultScene();

enum class RaySet { Primary, Diffuse, Shadow };
// `n` rays of a kind, as in shared/measurements/embree-limits.md: primary = one jittered
// camera ray per pixel in 16x16 tiles; diffuse = cosine-distributed rays from surface points
// chosen by area, in random order; shadow = segments between random surface points.
RayQueue makeRays(const Scene& scene, RaySet kind, size_t n, uint64_t seed = 1);

// Renders `scene` with `settings` once per iteration and reports rays/s, samples/s (named
// `samplesName`) and each stage's share of the stage time of the last render.
void benchmarkWholeRender(benchmark::State& state, const Scene& scene, const RenderSettings& settings,
                          const char* samplesName = "paths/s");

}  // namespace erpt::bench
