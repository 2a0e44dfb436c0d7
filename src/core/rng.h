// Counter-based random numbers: every value is a pure function of (seed, stream key,
// dimension), so results do not depend on thread count, scheduling or batch boundaries.
// The path tracer keys streams by (pixel, sample); ERPT will key them by (chain, step).
#pragma once

#include <cstdint>

namespace erpt {

// SplitMix64 finalizer: a bijective mixer with full avalanche.
inline uint64_t mix64(uint64_t z) {
  z += 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

inline uint64_t streamKey(uint64_t seed, uint64_t a, uint64_t b) { return mix64(mix64(seed ^ mix64(a)) + b); }

// Dimension d of a stream hashes key + (d + 1) * kDimensionStride (an odd constant, so the
// dimensions of one key never collide): the dimension's offset. Kernels that draw in vector
// lanes (kernels/uniform_lanes.h) take offsets.
constexpr uint64_t kDimensionStride = 0x632be59bd9b4e019ull;
inline uint64_t dimensionOffset(uint64_t key, uint32_t dim) { return key + kDimensionStride * (uint64_t(dim) + 1); }

// The 64 random bits of dimension `dim` of stream `key`; every draw below uses their top bits.
inline uint64_t uniformBits(uint64_t key, uint32_t dim) { return mix64(dimensionOffset(key, dim)); }

// A float in [0, 1) from the top 24 of 64 random bits.
inline float floatFromBits(uint64_t bits) { return float(bits >> 40) * 0x1p-24f; }

// Uniform float in [0, 1) for dimension `dim` of stream `key`: 24 bits, for continuous
// variables (positions, directions). Never scale it to an index or compare it with a
// probability that may be below 2^-24: use uniformIndex or uniformDouble.
inline float uniformFloat(uint64_t key, uint32_t dim) { return floatFromBits(uniformBits(key, dim)); }
inline uint32_t uniformUint(uint64_t key, uint32_t dim) { return uint32_t(uniformBits(key, dim) >> 32); }
// Uniform double in [0, 1), 53 bits, whose top 24 bits are uniformFloat's: for inverting
// discrete CDFs and for coins against small probabilities. Every float in [2^-29, 1) is a
// multiple of 2^-53, so P(a <= u < b) = b - a exactly for such floats a < b.
inline double doubleFromBits(uint64_t bits) { return double(bits >> 11) * 0x1p-53; }
inline double uniformDouble(uint64_t key, uint32_t dim) { return doubleFromBits(uniformBits(key, dim)); }

// Uniform integer in [0, n), n >= 1, with every value exactly equally likely: Lemire's
// multiply-shift on 64 bits, rejecting the low products that would favour some values (a
// rejection happens with probability below n / 2^64; it redraws from the next bits of a
// derived stream). floor(u * n) with a 24-bit float u is not uniform unless n is a power of 2.
inline uint64_t uniformIndex(uint64_t key, uint32_t dim, uint64_t n) {
  const uint64_t threshold = (0 - n) % n;  // 2^64 mod n
  uint64_t bits = uniformBits(key, dim);
  for (uint64_t attempt = 1;; ++attempt) {
    const unsigned __int128 product = (unsigned __int128)bits * n;
    if (uint64_t(product) >= threshold) return uint64_t(product >> 64);
    bits = mix64(bits + attempt);
  }
}

// A stream with a running dimension counter, for code that draws many numbers in sequence.
struct SampleStream {
  uint64_t key;
  uint32_t dim = 0;
  float next() { return uniformFloat(key, dim++); }
};

}  // namespace erpt

namespace erpt {

// A pseudo-random permutation of [0, n) indexed by `i`, chosen by `key` (Kensler 2013,
// "Correlated Multi-Jittered Sampling": a hash restricted to the next power of two, retried
// until it lands inside [0, n)). Used to pair strata across dimensions.
inline uint32_t permuteIndex(uint32_t i, uint32_t n, uint32_t key) {
  uint32_t w = n - 1;
  w |= w >> 1;
  w |= w >> 2;
  w |= w >> 4;
  w |= w >> 8;
  w |= w >> 16;
  do {
    i ^= key;
    i *= 0xe170893du;
    i ^= key >> 16;
    i ^= (i & w) >> 4;
    i ^= key >> 8;
    i *= 0x0929eb3fu;
    i ^= key >> 23;
    i ^= (i & w) >> 1;
    i *= 1u | key >> 27;
    i *= 0x6935fa69u;
    i ^= (i & w) >> 11;
    i *= 0x74dcb303u;
    i ^= (i & w) >> 2;
    i *= 0x9e501cc3u;
    i ^= (i & w) >> 2;
    i *= 0xc860a3dfu;
    i &= w;
    i ^= i >> 5;
  } while (i >= n);
  return (i + key) % n;
}

}  // namespace erpt
