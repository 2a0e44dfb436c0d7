#pragma once

#include <vector>

#include "erpt/erpt_settings.h"
#include "erpt/integrators.h"
#include "erpt/render.h"

namespace erpt {

// `--integrator erpt`: Energy Redistribution Path Tracing. `settings` must be resolved.
// Throws UsageError naming the option for absurd ERPT settings.
void validateErptSettings(const RenderSettings& settings);
// e_ave of ERPT's pilot pass: the mean energy per pixel sample of the seeds it redistributes.
double erptPilotEnergy(const Scene& scene, const RenderSettings& settings, RenderStats& stats);
RgbImage renderErpt(const Scene& scene, const RenderSettings& settings, RenderStats& stats);
// ERPT with e_ave and e_d known (time-budgeted passes share one pilot and a fixed e_d).
struct ErptEnergies {
  double pilot = -1;   // >= 0: e_ave, and no pilot pass
  double deposit = 0;  // > 0: e_d, instead of spp e_ave / M
};
RgbImage renderErptWith(const Scene& scene, const RenderSettings& settings, RenderStats& stats,
                        const ErptEnergies& known);
IntegratorModule erptModule();
}  // namespace erpt
