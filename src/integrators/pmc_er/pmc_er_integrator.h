#pragma once

#include "erpt/erpt_settings.h"
#include "erpt/pmc_settings.h"
#include "erpt/integrators.h"
#include "erpt/render.h"

namespace erpt {

// `--integrator pmc-er`: population Monte Carlo energy redistribution (docs/pmc-er.md).
// `settings` must be resolved. Throws UsageError naming the option for absurd settings.
void validatePmcSettings(const PmcSettings& settings, const ErptSettings& erpt);
RgbImage renderPmcEr(const Scene& scene, const RenderSettings& settings, RenderStats& stats);
IntegratorModule pmcErModule();

// The population a render with these settings runs: at most one member per position of its
// stratified pool (pixels x spp: the pool is the members' only source of paths, so further
// slots would hold resampled copies of the same ones). Throws UsageError when those members
// would need more than 80% of `availableBytes` (0: unknown, not checked), before anything is
// allocated or traced.
int usablePopulation(const RenderSettings& s, size_t availableBytes);

}  // namespace erpt
