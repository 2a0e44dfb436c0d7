#pragma once

#include <vector>

#include "erpt/integrators.h"
#include "erpt/render.h"

namespace erpt {

// `--integrator erpt`: Energy Redistribution Path Tracing. `settings` must be resolved.
// Throws UsageError naming the option for absurd ERPT settings.
void validateErptSettings(const ErptSettings& settings);
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
// Time-budgeted passes of ERPT, PMC-ER and MLT: the direct pass's samples per pixel follow the
// pass's share of the configured spp.
void scaleDirectSamples(const RenderSettings& whole, RenderSettings& pass);
// The direct-lighting pass of ERPT and PMC-ER (--direct-samples N > 0; else an empty image),
// with its own random stream; adds its rays and stage times to `stats`.
RgbImage renderDirectPass(const Scene& scene, const RenderSettings& settings, RenderStats& stats);
// The image ERPT and PMC-ER show: `chains` (the chains' image, resolved) plus `direct` (when
// not empty), then the proposed-mutations filter when `tally` (complete proposals per pixel)
// is given. With `extras`, the filter's extra images (proposals, raw, chains) go there.
RgbImage redistributionImage(const RenderSettings& settings, RgbImage chains, const RgbImage& direct,
                             const std::vector<uint32_t>* tally,
                             std::vector<std::pair<std::string, RgbImage>>* extras);

}  // namespace erpt
