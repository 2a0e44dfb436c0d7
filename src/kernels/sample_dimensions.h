// The random-number dimensions of one path-tracer sample: what each number of a camera
// sample's stream is used for. The stages draw them (stages.h); primary sample space
// (primary_samples.h) keeps them per chain.
#pragma once

#include <cstdint>

namespace erpt {

// Random-number dimensions of one camera sample (stream key = (pixel, sample)): two for the
// film position, then eight per bounce, so every number is addressed by (depth, use).
constexpr uint32_t kDimFilmX = 0, kDimFilmY = 1;
// The thin lens's disk sample: far from the per-bounce dimensions (a counter-based stream has
// them all), so pinhole renders keep their numbers.
constexpr uint32_t kDimLensX = 0x7fff0000u, kDimLensY = 0x7fff0001u;
enum BounceDim : uint32_t { kLightPick = 0, kLight1, kLight2, kLobe, kBsdf1, kBsdf2, kRoulette, kBounceDims = 8 };
inline uint32_t bounceDim(uint32_t depth, BounceDim use) { return 2 + kBounceDims * (depth - 1) + use; }

}  // namespace erpt
