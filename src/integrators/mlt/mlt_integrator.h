#pragma once

#include "erpt/erpt_settings.h"
#include "erpt/mlt_settings.h"
#include "erpt/integrators.h"
#include "erpt/render.h"

namespace erpt {

// `--integrator mlt`: Metropolis light transport over ERPT's mutation engine (docs/mlt.md).
// `settings` must be resolved. Throws UsageError naming the option for absurd settings.
void validateMltSettings(const RenderSettings& settings);
RgbImage renderMlt(const Scene& scene, const RenderSettings& settings, RenderStats& stats);
IntegratorModule mltModule();
// The Metropolis options mlt and pssmlt share (MltSettings): large-step probability,
// bootstrap, chains.
std::vector<OptionSpec> metropolisOptions();

}  // namespace erpt
