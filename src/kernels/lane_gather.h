// A batch gathered from a column by lane indices. xsimd 8's batch::gather misses the AVX2
// gather instruction for the fma3<avx2> lanes (lane_arch.h) and falls back to a per-lane loop
// behind a call (9% of the diffuse shade kernel's time), so with AVX2 lanes the intrinsic is
// called directly.
#pragma once

#include <cstdint>
#include <type_traits>

#include "kernels/lane_arch.h"
#if XSIMD_WITH_AVX2
#include <immintrin.h>
#endif

namespace erpt {

template <class T>
LaneBatch<T> gatherLanes(const T* column, const LaneBatch<int32_t>& index) {
  static_assert(sizeof(T) == 4, "32-bit elements, one per index lane");
#if XSIMD_WITH_AVX2
  if constexpr (std::is_same_v<T, float>) return _mm256_i32gather_ps(column, index, 4);
  else return _mm256_i32gather_epi32(reinterpret_cast<const int*>(column), index, 4);
#else
  return LaneBatch<T>::gather(column, index);
#endif
}

}  // namespace erpt
