// Options of `--integrator bdpt` (docs/bdpt.md).
#pragma once

namespace erpt {

struct BdptSettings {
  // --bdpt-s / --bdpt-t: render only the strategies with this many light (s) or camera (t)
  // vertices (-1: all), as pbrt's strategy visualisation does; --bdpt-weights none leaves their
  // MIS weights out, so that one strategy alone estimates every path it can make.
  int onlyS = -1, onlyT = -1;
  bool unweighted = false;
};

// The BdptSettings of a RenderSettings (its `options`): bdptOf(settings).field.
template <class Settings>
auto& bdptOf(Settings& settings) {
  return settings.options.template get<BdptSettings>();
}

}  // namespace erpt
