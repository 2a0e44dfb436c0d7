#pragma once

#include <vector>

#include "erpt/render.h"

namespace erpt {

// `--integrator erpt`: Energy Redistribution Path Tracing. `settings` must be resolved.
// Throws UsageError naming the option for absurd ERPT settings.
void validateErptSettings(const ErptSettings& settings);
// e_ave of ERPT's pilot pass: the mean energy per pixel sample of the seeds it redistributes.
double erptPilotEnergy(const Scene& scene, const RenderSettings& settings, RenderStats& stats);
RgbImage renderErpt(const Scene& scene, const RenderSettings& settings, RenderStats& stats);
// What ERPT and PMC-ER do after their chains: `image` (the chains' image, resolved) plus the
// direct-lighting pass (--direct-samples), then the proposed-mutations filter when `tally`
// (complete proposals per pixel) is given, with its extra images.
RgbImage finishRedistribution(const Scene& scene, const RenderSettings& settings, RenderStats& stats, RgbImage image,
                              const std::vector<uint32_t>* tally);

}  // namespace erpt
