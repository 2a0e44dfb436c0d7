// What a front end (the CLI, the Python module) asks to render, as its user gave it, and the one
// translation of that into RenderSettings: the same request gives the same settings, and so
// the same image, from either front end.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "erpt/render.h"
#include "erpt/scene.h"

namespace erpt {

// The ranges of the options every integrator takes: the CLI's checks and the Python module's
// (which refuse a value out of range as the CLI does) read them here.
struct CommonOptionRange {
  double low, high;
};
constexpr CommonOptionRange kSppRange{1, 1 << 24}, kImageSizeRange{1, 65536}, kThreadsRange{0, 1024},
    kMaxDepthRange{-1, 100000}, kTimeRange{1e-3, 1e7};

struct RenderRequest {
  std::string integrator;  // empty: the scene's, if it is one of ours, else the default
  int spp = 0, width = 0, height = 0, threads = 0;
  int maxDepth = -2;  // -2: the scene's; -1: unbounded; 0 is refused
  uint64_t seed = 0;
  double time = 0;     // > 0: a time budget in seconds instead of spp
  std::string filter;  // box, tent or gaussian; empty: the scene's
  // Long names ("--spp") of every option given, the common ones included: `--spp` given with
  // an integrator whose sppOption is set means that option (MLT's mutations per pixel).
  std::vector<std::string> given;
  // The integrators' own options as given, by name without dashes, as text ("true" for a flag).
  std::vector<std::pair<std::string, std::string>> options;
};

// The integrators that declare `option` ("--name"; for the sample-pass options of
// kSamplePassOptions, those that render in sample passes). Empty: no integrator declares it,
// so it is a common option every integrator takes.
std::vector<std::string> integratorsUsing(const std::string& option);

// Throws UsageError for the first given option ("--name") that none of `integrators` uses,
// naming it and the integrators that do.
void checkOptionScope(const std::vector<std::string>& given, const std::vector<std::string>& integrators);

// The settings of a request, before resolveSettings: its integrator (an unknown name is
// refused), the common fields, and the options that integrator declares, applied through its
// option table. Options it does not declare are left to checkOptionScope. `note`, when given,
// receives a line to show when the scene asks for an integrator we do not have.
RenderSettings settingsFor(const Scene& scene, const RenderRequest& request, std::string* note = nullptr);

}  // namespace erpt
