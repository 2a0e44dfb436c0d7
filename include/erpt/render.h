// Rendering entry point shared by the CLI, tests and benchmarks.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "erpt/erpt_settings.h"
#include "erpt/image_io.h"
#include "erpt/parallel.h"
#include "erpt/scene.h"
#include "erpt/seeds.h"

namespace erpt {

struct RenderSettings {
  std::string integrator = "path";
  int width = 0, height = 0;  // 0: the scene's film size
  int spp = 0;                // 0: the scene's sample count
  int maxDepth = -2;          // -2: the scene's value
  uint64_t seed = 0;
  int threads = 0;            // 0: all hardware threads
  bool filterSet = false;     // false: the scene's rfilter
  FilterKind filter = FilterKind::Box;
  std::function<void(double fraction)> progress;  // called from the rendering thread
  SeedStore* seeds = nullptr;  // path tracer: when set, every contribution is recorded as a seed
  // Path tracer with `seeds` set: called after every batch with that batch's seeds, which are
  // then cleared (streaming, so memory stays bounded). Unset: the store keeps all seeds.
  std::function<void(SeedStore&)> seedSink;
  ErptSettings erpt;
};

struct RenderStats {
  double seconds = 0;
  uint64_t samples = 0;
  uint64_t rays = 0;
  uint64_t invalidSamples = 0;  // NaN/Inf estimates, dropped and counted
  StageTimes stages;
  ErptStats erpt;
};

// Settings with the scene's values filled in where the caller left them open.
RenderSettings resolveSettings(const Scene& scene, RenderSettings settings);
// Names of the integrators render() knows.
const char* integratorNames();
// Throws UsageError for an unknown integrator.
RgbImage render(const Scene& scene, const RenderSettings& settings, RenderStats& stats);

}  // namespace erpt
