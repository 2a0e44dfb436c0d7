#pragma once

#include "erpt/integrators.h"
#include "erpt/mlt_settings.h"
#include "erpt/pssmlt_settings.h"
#include "erpt/render.h"

namespace erpt {

// `--integrator pssmlt`: primary-sample-space MLT over the path tracer (docs/pssmlt.md).
// `settings` must be resolved. Throws UsageError naming the option for absurd settings.
void validatePssmltSettings(const RenderSettings& settings);
RgbImage renderPssmlt(const Scene& scene, const RenderSettings& settings, RenderStats& stats);
IntegratorModule pssmltModule();

void addPssmltStats(PssmltStats& to, const PssmltStats& from);
void printPssmltSummary(const RenderStats& stats);

}  // namespace erpt
