// The AVX2 lanes: SplitMix64 on four 64-bit lanes (kernels/mix64_lanes.h), Kensler's
// permutation on eight 32-bit lanes, each lane retrying until it lands inside [0, spp) as the
// scalar loop does, and the final modulo in double lanes (exact, see permuteLanes).
#include "kernels/pixel_strata.h"

#include "core/rng.h"
#include "kernels/mix64_lanes.h"

namespace erpt {

namespace {

// The scalar definition, which the lanes reproduce.
void pixelStrataOne(uint64_t seed, uint32_t spp, uint32_t dimX, uint32_t dimY, uint32_t pixel, uint32_t sample,
                    float& ux, float& uy) {
  const uint64_t key = streamKey(seed, pixel, sample);
  const uint32_t block = sample / spp, s = sample % spp;
  const uint32_t keyX = uint32_t(streamKey(seed, pixel, ~1ull - 2 * uint64_t(block))),
                 keyY = uint32_t(streamKey(seed, pixel, ~0ull - 2 * uint64_t(block)));
  ux = (float(permuteIndex(s, spp, keyX)) + uniformFloat(key, dimX)) / float(spp);
  uy = (float(permuteIndex(s, spp, keyY)) + uniformFloat(key, dimY)) / float(spp);
}

#if defined(__AVX2__)
// The low 32 bits of each of two vectors' four 64-bit lanes, as eight 32-bit lanes.
__m256i lowHalves(__m256i first, __m256i second) {
  const __m256i pick = _mm256_setr_epi32(0, 2, 4, 6, 1, 3, 5, 7);
  const __m128i a = _mm256_castsi256_si128(_mm256_permutevar8x32_epi32(first, pick));
  const __m128i b = _mm256_castsi256_si128(_mm256_permutevar8x32_epi32(second, pick));
  return _mm256_inserti128_si256(_mm256_castsi128_si256(a), b, 1);
}

__m256i mul32(__m256i a, uint32_t b) { return _mm256_mullo_epi32(a, _mm256_set1_epi32(int32_t(b))); }

// permuteIndex of rng.h on eight lanes with the same n (below 2^31).
__m256i permuteLanes(__m256i i, uint32_t n, __m256i key) {
  uint32_t w = n - 1;
  w |= w >> 1, w |= w >> 2, w |= w >> 4, w |= w >> 8, w |= w >> 16;
  const __m256i mask = _mm256_set1_epi32(int32_t(w)), last = _mm256_set1_epi32(int32_t(n - 1));
  auto xorMaskedShift = [&](__m256i v, int shift) {
    return _mm256_xor_si256(v, _mm256_srli_epi32(_mm256_and_si256(v, mask), shift));
  };
  const __m256i keyMul = _mm256_or_si256(_mm256_set1_epi32(1), _mm256_srli_epi32(key, 27));
  __m256i retry = _mm256_set1_epi32(-1);
  do {
    __m256i v = _mm256_xor_si256(i, key);
    v = mul32(v, 0xe170893du);
    v = _mm256_xor_si256(v, _mm256_srli_epi32(key, 16));
    v = xorMaskedShift(v, 4);
    v = _mm256_xor_si256(v, _mm256_srli_epi32(key, 8));
    v = mul32(v, 0x0929eb3fu);
    v = _mm256_xor_si256(v, _mm256_srli_epi32(key, 23));
    v = xorMaskedShift(v, 1);
    v = _mm256_mullo_epi32(v, keyMul);
    v = mul32(v, 0x6935fa69u);
    v = xorMaskedShift(v, 11);
    v = mul32(v, 0x74dcb303u);
    v = xorMaskedShift(v, 2);
    v = mul32(v, 0x9e501cc3u);
    v = xorMaskedShift(v, 2);
    v = mul32(v, 0xc860a3dfu);
    v = _mm256_and_si256(v, mask);
    v = _mm256_xor_si256(v, _mm256_srli_epi32(v, 5));
    i = _mm256_blendv_epi8(i, v, retry);  // lanes already inside keep their value
    retry = _mm256_and_si256(retry, _mm256_cmpgt_epi32(i, last));  // i <= w < 2^31: signed compare
  } while (!_mm256_testz_si256(retry, retry));
  // (i + key) % n, the sum a wrapping at 2^32 as in the scalar code, in double: a / n is off
  // by at most a / n * 2^-53 < 2^-21 / n, less than its distance 1 / n from the next integer
  // when it is not one, so its floor is exact, and so is a - floor * n.
  const __m256i sum = _mm256_add_epi32(i, key);
  const __m256d nd = _mm256_set1_pd(double(n)), two32 = _mm256_set1_pd(0x1p32), zero = _mm256_setzero_pd();
  auto modulo = [&](__m128i half) {
    __m256d a = _mm256_cvtepi32_pd(half);  // signed: lanes of 2^31 and above come out 2^32 low
    a = _mm256_add_pd(a, _mm256_and_pd(_mm256_cmp_pd(a, zero, _CMP_LT_OQ), two32));
    const __m256d q = _mm256_floor_pd(_mm256_div_pd(a, nd));
    return _mm256_cvtpd_epi32(_mm256_sub_pd(a, _mm256_mul_pd(q, nd)));
  };
  const __m128i low = modulo(_mm256_castsi256_si128(sum)), high = modulo(_mm256_extracti128_si256(sum, 1));
  return _mm256_inserti128_si256(_mm256_castsi128_si256(low), high, 1);
}

#endif

}  // namespace

void pixelStrata(uint64_t seed, uint32_t spp, uint32_t dimX, uint32_t dimY, const uint32_t* pixels,
                 const uint32_t* samples, size_t n, float* ux, float* uy) {
  size_t i = 0;
#if defined(__AVX2__)
  if (spp < (1u << 24)) {  // strata and offsets exact in float lanes, as they are in the scalar code
    const __m256i seedLanes = _mm256_set1_epi64x(int64_t(seed));
    const __m256i offsetX = _mm256_set1_epi64x(int64_t(kDimensionStride * (uint64_t(dimX) + 1)));
    const __m256i offsetY = _mm256_set1_epi64x(int64_t(kDimensionStride * (uint64_t(dimY) + 1)));
    const __m256 sppLanes = _mm256_set1_ps(float(spp));
    for (; i + 8 <= n; i += 8) {
      alignas(32) uint32_t block[8], within[8];
      for (int j = 0; j < 8; ++j) block[j] = samples[i + j] / spp, within[j] = samples[i + j] % spp;
      __m256i keyX[2], keyY[2];
      __m128 offX[2], offY[2];
      for (int half = 0; half < 2; ++half) {
        auto widen = [&](const uint32_t* v) {
          return _mm256_cvtepu32_epi64(_mm_loadu_si128(reinterpret_cast<const __m128i*>(v + 4 * half)));
        };
        // streamKey(seed, pixel, b) = mix64(mix64(seed ^ mix64(pixel)) + b): the inner part is shared.
        const __m256i pixelHash = mix64Lanes(_mm256_xor_si256(seedLanes, mix64Lanes(widen(pixels + i))));
        const __m256i key = mix64Lanes(_mm256_add_epi64(pixelHash, widen(samples + i)));
        const __m256i twiceBlock = _mm256_slli_epi64(widen(block), 1);
        keyX[half] = mix64Lanes(_mm256_add_epi64(pixelHash, _mm256_sub_epi64(_mm256_set1_epi64x(int64_t(~1ull)), twiceBlock)));
        keyY[half] = mix64Lanes(_mm256_add_epi64(pixelHash, _mm256_sub_epi64(_mm256_set1_epi64x(int64_t(~0ull)), twiceBlock)));
        offX[half] = floatsFromBitsLanes(mix64Lanes(_mm256_add_epi64(key, offsetX)));
        offY[half] = floatsFromBitsLanes(mix64Lanes(_mm256_add_epi64(key, offsetY)));
      }
      const __m256i s = _mm256_load_si256(reinterpret_cast<const __m256i*>(within));
      const __m256i strataX = permuteLanes(s, spp, lowHalves(keyX[0], keyX[1]));
      const __m256i strataY = permuteLanes(s, spp, lowHalves(keyY[0], keyY[1]));
      const __m256 fx = _mm256_insertf128_ps(_mm256_castps128_ps256(offX[0]), offX[1], 1);
      const __m256 fy = _mm256_insertf128_ps(_mm256_castps128_ps256(offY[0]), offY[1], 1);
      _mm256_storeu_ps(ux + i, _mm256_div_ps(_mm256_add_ps(_mm256_cvtepi32_ps(strataX), fx), sppLanes));
      _mm256_storeu_ps(uy + i, _mm256_div_ps(_mm256_add_ps(_mm256_cvtepi32_ps(strataY), fy), sppLanes));
    }
  }
#endif
  for (; i < n; ++i) pixelStrataOne(seed, spp, dimX, dimY, pixels[i], samples[i], ux[i], uy[i]);
}

}  // namespace erpt
