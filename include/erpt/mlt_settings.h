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
  // --bootstrap: seed-sampler samples per pixel estimating b; 0: sized by the render
  // (bootstrapSamplesPerPixel).
  int bootstrapSpp = 0;
  int chains = 2048;                  // --chains: Markov chains, started by resampling the bootstrap
};

// What one bootstrap sample costs in chain steps (Cornell box, 128x128, 2 threads: 7 for a
// path-tracer sample, 77 for a BDPT sample, which traces both subpaths and every connection).
constexpr double kPathSampleSteps = 8, kBdptSampleSteps = 64;

// The bootstrap's samples per pixel for an image of `pixels` pixels whose chains take
// `mutationsPerPixel` steps per pixel, with seed samples costing `sampleSteps` chain steps each.
// By default, as many as cost about what the chains do, and at most 100,000 samples in all
// (pbrt-v4's bootstrap): b's error is the same share of every pixel, so beyond the chains' own
// cost a larger bootstrap buys less than longer chains would. At least 1 per pixel, so that
// the contributions the chains do not hold, deposited where the bootstrap found them, reach
// every pixel.
inline int bootstrapSamplesPerPixel(const MltSettings& m, double pixels, double mutationsPerPixel, double sampleSteps) {
  if (m.bootstrapSpp > 0) return m.bootstrapSpp;
  const double byCost = std::ceil(mutationsPerPixel / sampleSteps);
  const double byCount = std::ceil(100000.0 / std::max(1.0, pixels));
  return int(std::max(1.0, std::min(byCost, byCount)));
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
