#pragma once

#include "erpt/render.h"

namespace erpt {

// `settings` must be resolved (resolveSettings).
RgbImage renderPath(const Scene& scene, const RenderSettings& settings, RenderStats& stats);

}  // namespace erpt
