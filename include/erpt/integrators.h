// The integrators by name. The registry (src/integrators/registry.cpp) is the only place that
// maps a name to an integrator; the CLI takes the names, help and option scopes from it, and
// render() dispatches through it. Each integrator declares itself in its own file
// (`xxxModule()` beside its render function): what it is, the options it takes, how it
// validates its settings and how it renders.
#pragma once

#include <string>
#include <vector>

#include "erpt/render.h"

namespace erpt {

struct IntegratorModule {
  std::string name;         // --integrator NAME
  std::string description;  // one line, for --help
  // The options it takes besides those every integrator takes (size, threads, seed, depth,
  // filter, -D, spheres, --spp, --time, output), by their long names. An option given to an
  // integrator that does not declare it is refused.
  std::vector<std::string> options;
  // Throws UsageError (naming the option) for settings it cannot render; render() calls it
  // before building the BVH, so that bad options fail fast.
  void (*validate)(const RenderSettings& settings) = nullptr;
  RgbImage (*render)(const Scene& scene, const RenderSettings& settings, RenderStats& stats) = nullptr;
  // Its own lines of the end-of-render summary, after the common one (stderr). Optional.
  void (*printSummary)(const RenderStats& stats) = nullptr;

  // Time-budgeted renders (render.h) run it in independent passes of growing spp. Optional:
  // once before the first pass, what every pass shares (ERPT: one pilot and a fixed e_d);
  // before each pass (its spp set), what the configured spp scales (MLT's mutations, the
  // direct pass's samples).
  void (*prepareTimedPasses)(const Scene& scene, const RenderSettings& whole, RenderSettings& pass,
                             RenderStats& stats) = nullptr;
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

}  // namespace erpt
