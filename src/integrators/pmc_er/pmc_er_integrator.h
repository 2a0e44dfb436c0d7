#pragma once

#include "erpt/erpt_settings.h"
#include "erpt/pmc_settings.h"
#include "erpt/integrators.h"
#include "erpt/render.h"

namespace erpt {

// `--integrator pmc-er`: population Monte Carlo energy redistribution (docs/pmc-er.md).
// `settings` must be resolved. Throws UsageError naming the option for absurd settings.
void validatePmcSettings(const PmcSettings& settings, const ChainOptions& chains);
RgbImage renderPmcEr(const Scene& scene, const RenderSettings& settings, RenderStats& stats);
IntegratorModule pmcErModule();

// The population a render with these settings runs: at most one member per position of its
// stratified pool (pixels x spp: the pool is the members' only source of paths, so further
// slots would hold resampled copies of the same ones). Throws UsageError when those members
// would need more than 80% of `availableBytes` (0: unknown, not checked), before anything is
// allocated or traced.
int usablePopulation(const RenderSettings& s, size_t availableBytes);

struct RenderSetup;
struct StepConfig;
struct StepSettings;
class PmcMixture;
// The chain step's view of PMC-ER's kernel (the mixture picks the sizes).
StepSettings pmcStepSettings(const RenderSettings& s);
// What a PMC-ER render under --time shares with one of fixed spp (renderPmcEr sets them up and
// trains the mixture's region table first).
struct PmcTimeParts {
  RenderSetup& setup;
  const StepConfig& ctx;
  PmcMixture& mixture;
  double start;  // the render's start on budgetSeconds' clock: the budget counts from it
};
// --time: one population over an open-ended pool, taking whole rounds while the next fits in
// the budget (pmc_time_budget.cpp); sets stats.spp to the rounds taken.
RgbImage renderPmcForTime(const Scene& scene, const RenderSettings& s, const PmcTimeParts& parts, RenderStats& stats);

}  // namespace erpt
