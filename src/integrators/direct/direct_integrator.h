#pragma once

#include "erpt/integrators.h"
#include "erpt/render.h"

namespace erpt {

// `settings` must be resolved (resolveSettings).
RgbImage renderDirect(const Scene& scene, const RenderSettings& settings, RenderStats& stats);
IntegratorModule directModule();

}  // namespace erpt
