#pragma once

#include "erpt/render.h"

namespace erpt {

// `--integrator erpt`: Energy Redistribution Path Tracing. `settings` must be resolved.
// e_ave of ERPT's pilot pass: the mean energy per pixel sample of the seeds it redistributes.
double erptPilotEnergy(const Scene& scene, const RenderSettings& settings, RenderStats& stats);
RgbImage renderErpt(const Scene& scene, const RenderSettings& settings, RenderStats& stats);

}  // namespace erpt
