// The random-number dimensions of one path-tracer or BDPT sample: what each number of a
// sample's streams is used for. The stages draw them (stages.h); primary sample space
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

// A BDPT sample's light subpath draws from a stream of its own: its emission sample (the light
// pick, then four numbers) apart from the bounces (bounceDim, as the camera subpath's) and, for
// light tracing, the lens point (kDimLensX, kDimLensY).
constexpr uint32_t kDimEmitPick = 0x7ffe0000u, kDimEmit1 = kDimEmitPick + 1, kEmitDims = 5;
// Multiplexed MLT's choice of a BDPT strategy, a number of the camera subpath's stream.
constexpr uint32_t kDimBdptStrategy = 0x7ffd0000u;
// Replaying primary samples (primary_samples.h), a stream key is a chain's index, with this bit
// set for its light subpath's numbers.
constexpr uint64_t kLightSubpathStream = uint64_t(1) << 63;

}  // namespace erpt
