#pragma once

#include "erpt/render.h"

namespace erpt {

// `--integrator pmc-er`: population Monte Carlo energy redistribution (docs/pmc-er.md).
// `settings` must be resolved. Throws UsageError naming the option for absurd settings.
void validatePmcSettings(const PmcSettings& settings, const ErptSettings& erpt);
RgbImage renderPmcEr(const Scene& scene, const RenderSettings& settings, RenderStats& stats);

}  // namespace erpt
