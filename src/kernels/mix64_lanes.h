// mix64 of core/rng.h on four 64-bit AVX2 lanes, and uniformFloat's conversion of its bits.
// AVX2 has no 64-bit multiply; mix64's two multiplies by constants are built from three
// 32x32 -> 64-bit ones each (the high half of a product of high halves falls off the low
// 64 bits). Only for code compiled with AVX2.
#pragma once

#if defined(__AVX2__)
#include <immintrin.h>

#include <cstdint>

namespace erpt {

// The low 64 bits of a * b in each lane.
inline __m256i mulLow64(__m256i a, uint64_t b) {
  const __m256i bLow = _mm256_set1_epi64x(int64_t(b & 0xffffffffu)), bHigh = _mm256_set1_epi64x(int64_t(b >> 32));
  const __m256i cross = _mm256_add_epi64(_mm256_mul_epu32(_mm256_srli_epi64(a, 32), bLow), _mm256_mul_epu32(a, bHigh));
  return _mm256_add_epi64(_mm256_mul_epu32(a, bLow), _mm256_slli_epi64(cross, 32));
}

inline __m256i mix64Lanes(__m256i z) {
  z = _mm256_add_epi64(z, _mm256_set1_epi64x(int64_t(0x9e3779b97f4a7c15ull)));
  z = mulLow64(_mm256_xor_si256(z, _mm256_srli_epi64(z, 30)), 0xbf58476d1ce4e5b9ull);
  z = mulLow64(_mm256_xor_si256(z, _mm256_srli_epi64(z, 27)), 0x94d049bb133111ebull);
  return _mm256_xor_si256(z, _mm256_srli_epi64(z, 31));
}

// floatFromBits of each lane: the top 24 bits, moved to the low dwords and converted.
inline __m128 floatsFromBitsLanes(__m256i bits) {
  const __m256i top = _mm256_permutevar8x32_epi32(_mm256_srli_epi64(bits, 40), _mm256_setr_epi32(0, 2, 4, 6, 1, 3, 5, 7));
  return _mm_mul_ps(_mm_cvtepi32_ps(_mm256_castsi256_si128(top)), _mm_set1_ps(0x1p-24f));
}

}  // namespace erpt
#endif
