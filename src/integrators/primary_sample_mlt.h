// Primary-sample-space MLT, the engine of `pssmlt` and `mmlt` (docs/pssmlt.md).
#pragma once

#include "erpt/pssmlt_settings.h"
#include "erpt/render.h"

namespace erpt {

// multiplexed: mmlt (one chain per path length of its start, one BDPT strategy per sample);
// else pssmlt (the path tracer or BDPT, --seeds). `settings` must be resolved. Throws
// UsageError naming the option for settings it cannot render.
void validatePrimarySampleMlt(const RenderSettings& settings, bool multiplexed);
RgbImage renderPrimarySampleMlt(const Scene& scene, const RenderSettings& settings, RenderStats& stats,
                                bool multiplexed);
// mmlt's longest path in segments: --max-depth, or 6 (pbrt-v4's five bounces) when unbounded.
int mmltLongestPath(const RenderSettings& settings);

void addPssmltStats(PssmltStats& to, const PssmltStats& from);
// name: the integrator's, which starts each line.
void printPrimarySampleSummary(const char* name, const RenderStats& stats);

}  // namespace erpt
