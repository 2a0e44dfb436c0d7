#pragma once

#include "erpt/render.h"

namespace erpt {

// `--integrator erpt`: Energy Redistribution Path Tracing. `settings` must be resolved.
// Throws UsageError naming the option for absurd ERPT settings.
void validateErptSettings(const ErptSettings& settings);
// e_ave of ERPT's pilot pass: the mean energy per pixel sample of the seeds it redistributes.
double erptPilotEnergy(const Scene& scene, const RenderSettings& settings, RenderStats& stats);
RgbImage renderErpt(const Scene& scene, const RenderSettings& settings, RenderStats& stats);

}  // namespace erpt
