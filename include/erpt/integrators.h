// The integrators by name. The registry (src/integrators/registry.cpp) is the only place that
// maps a name to an integrator; the CLI takes the names, help and option scopes from it, and
// render() dispatches through it. Each integrator declares itself in its own file
// (`xxxModule()` beside its render function): what it is, the options it takes, how it
// validates its settings and how it renders.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "erpt/options.h"
#include "erpt/render.h"

namespace erpt {

// Renders one pass of a time-budgeted render.
using PassRenderer = std::function<RgbImage(const Scene& scene, const RenderSettings& pass, RenderStats& stats)>;

struct IntegratorModule {
  std::string name;         // --integrator NAME
  std::string description;  // one line, for --help
  // The options it takes besides those every integrator takes (size, threads, seed, depth,
  // filter, -D, spheres, --spp, --time, output), each declared once (options.h). An option
  // given to an integrator that does not declare it is refused.
  std::vector<OptionSpec> options;
  // It renders in sample passes (sample_passes.h), so the front end may checkpoint it, write
  // its partial images and stream them to a viewer (kSamplePassOptions).
  bool samplePasses = false;
  // The option that --spp sets for it, when --spp means something else than samples per
  // pixel (MLT: the mutations per pixel, as Mitsuba's sample count; its spp is then 1, and
  // time-budgeted passes scale the option by theirs); empty: samples per pixel.
  std::string sppOption;
  // Throws UsageError (naming the option) for settings it cannot render; render() calls it
  // before building the BVH, so that bad options fail fast.
  void (*validate)(const RenderSettings& settings) = nullptr;
  RgbImage (*render)(const Scene& scene, const RenderSettings& settings, RenderStats& stats) = nullptr;
  // Its own lines of the end-of-render summary, after the common one (stderr). Optional.
  void (*printSummary)(const RenderStats& stats) = nullptr;
  // Adds its own statistics of one time-budgeted pass (`from`) to the render's (`to`); the
  // common ones (samples, rays, stage times) are added by render(). Optional.
  void (*addStats)(RenderStats& to, const RenderStats& from) = nullptr;

  // It keeps to a time budget itself: render() hands it settings with timeBudget > 0 instead
  // of running it in independent passes (PMC-ER keeps one population iterating).
  bool ownTimeBudget = false;
  // Otherwise time-budgeted renders (render.h) run it in independent passes of growing spp. Optional:
  // once before the first pass, what every pass shares (ERPT: one pilot and a fixed e_d),
  // returned as the function that renders a pass (unset: `render`); before each pass (its spp
  // set), what the configured spp scales (MLT's mutations, the direct pass's samples).
  PassRenderer (*timedPasses)(const Scene& scene, const RenderSettings& whole, RenderStats& stats) = nullptr;
  void (*scaleTimedPass)(const RenderSettings& whole, RenderSettings& pass) = nullptr;
  // Its image may carry the proposed-mutations filter, which is not linear: over passes it is
  // applied once, to the sum of the passes' chain images and tallies.
  bool proposalFiltered = false;
};

// Every integrator, in the order --help lists them.
const std::vector<IntegratorModule>& integratorModules();
// The integrator of that name, or nullptr.
const IntegratorModule* findIntegrator(const std::string& name);
// The integrator of that name; throws UsageError naming the ones there are.
const IntegratorModule& integratorNamed(const std::string& name);
// "path, direct, erpt, ...", for messages.
std::string integratorNames();
// The integrator a scene or caller that names none gets.
const IntegratorModule& defaultIntegrator();
// Its declaration of `--name` (name without dashes), or nullptr.
const OptionSpec* findOption(const IntegratorModule& integrator, const std::string& name);

// Sets the options `given` (long names without dashes, with their text; "true" for a flag) that
// the integrator declares, in its declaration order, then throws UsageError for one that has no
// effect with the result (OptionSpec::inapplicable). Options it does not declare are skipped:
// front ends refuse them by scope (the CLI says which integrators take them).
void applyOptions(const IntegratorModule& integrator, const std::vector<std::pair<std::string, std::string>>& given,
                  RenderSettings& settings);

// The front-end options of integrators that render in sample passes (long names): checkpoints,
// partial images and the tev display (docs/long-renders.md).
inline const std::vector<std::string> kSamplePassOptions = {"--checkpoint", "--checkpoint-every", "--write-partial",
                                                            "--display"};

}  // namespace erpt
