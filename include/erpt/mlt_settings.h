// Options and statistics of `--integrator mlt` (Metropolis light transport over ERPT's mutation
// engine; docs/mlt.md). The mutation options (strategy, lens radius, caustic angle, direct
// split, mutations per pixel) are the chain integrators' shared ones (ChainOptions).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace erpt {

struct MltSettings {
  float largeStepProbability = 0.3f;  // --large-step-prob (Mitsuba's and pbrt's default)
  // --bootstrap: path-tracer samples per pixel estimating b; 0: enough for 100,000 samples
  // (pbrt-v4's default bootstrap), at least 1 per pixel.
  int bootstrapSpp = 0;
  int chains = 2048;                  // --chains: Markov chains, started by resampling the bootstrap
};

// The bootstrap's samples per pixel for an image of `pixels` pixels.
inline int bootstrapSamplesPerPixel(const MltSettings& m, double pixels) {
  if (m.bootstrapSpp > 0) return m.bootstrapSpp;
  return int(std::max(1.0, std::ceil(100000.0 / std::max(1.0, pixels))));
}

struct MltStats {
  double b = 0;                  // the bootstrap's estimate of the chains' total image luminance
  double inPlaceEnergy = 0;      // the bootstrap's estimate of what the chains do not hold (luminance)
  uint64_t bootstrapSamples = 0;
  uint64_t domainSeeds = 0;      // bootstrap contributions the chains hold (resampled from)
  uint64_t inPlaceSeeds = 0;     // bootstrap contributions they do not (deposited where they are)
  uint64_t chains = 0, chainLength = 0;
  double energyPerStep = 0;      // b / (chains x chain length)
  double chainSeconds = 0, bootstrapSeconds = 0;
};

// The MltSettings of a RenderSettings (its `options`): mltOf(settings).field.
template <class Settings>
auto& mltOf(Settings& settings) {
  return settings.options.template get<MltSettings>();
}

// The MltStats of a RenderStats (its `own`): mltStatsOf(stats).field.
template <class Stats>
auto& mltStatsOf(Stats& stats) {
  return stats.own.template get<MltStats>();
}

}  // namespace erpt
