// Options and statistics of `--integrator pssmlt` (primary-sample-space MLT, Kelemen et al.
// 2002, over the path tracer or BDPT) and `--integrator mmlt` (multiplexed MLT, Hachisuka et
// al. 2014, over BDPT's strategies): docs/pssmlt.md. Their large-step probability, bootstrap
// and chain count are MLT's options (MltSettings), their steps per pixel the chain
// integrators' --mutations-per-pixel.
#pragma once

#include <cstdint>

namespace erpt {

struct PssmltSettings {
  // --small-step: Kelemen's s2, the largest offset of a small step in primary sample space
  // (s1 = s2 / 16); 1/64 as in the paper and in Mitsuba 0.6.
  double smallStep = 1.0 / 64;
  // --sigma (mmlt): the standard deviation of a small step's normal offset; pbrt-v4's 0.01.
  double sigma = 0.01;
};

struct PssmltStats {
  double b = 0;  // the bootstrap's estimate of the image's mean luminance per primary sample
  uint64_t bootstrapSamples = 0;
  uint64_t chains = 0, chainLength = 0;
  uint64_t smallSteps = 0, smallAccepted = 0, largeSteps = 0, largeAccepted = 0;
  uint64_t invalidProposals = 0;  // proposals whose radiance was not finite (rejected)
  uint64_t rays = 0;
  double bootstrapSeconds = 0, chainSeconds = 0;
};

template <class Settings>
auto& pssmltOf(Settings& settings) {
  return settings.options.template get<PssmltSettings>();
}

template <class Stats>
auto& pssmltStatsOf(Stats& stats) {
  return stats.own.template get<PssmltStats>();
}

}  // namespace erpt
