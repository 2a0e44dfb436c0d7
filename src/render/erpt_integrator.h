#pragma once

#include "erpt/render.h"

namespace erpt {

// `--integrator erpt`: Energy Redistribution Path Tracing. `settings` must be resolved.
RgbImage renderErpt(const Scene& scene, const RenderSettings& settings, RenderStats& stats);

}  // namespace erpt
