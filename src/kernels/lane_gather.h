// A batch gathered from a column by lane indices. xsimd 8's batch::gather misses the AVX2
// gather instruction for the fma3<avx2> architecture this library is compiled for and falls
// back to a per-lane loop behind a call (9% of the diffuse shade kernel's time), so with AVX2
// batches the intrinsic is called directly.
#pragma once

#include <cstdint>
#include <type_traits>

#include <xsimd/xsimd.hpp>
#if XSIMD_WITH_AVX2
#include <immintrin.h>
#endif

namespace erpt {

template <class T>
xsimd::batch<T> gatherLanes(const T* column, const xsimd::batch<int32_t>& index) {
  static_assert(sizeof(T) == 4, "32-bit elements, one per index lane");
#if XSIMD_WITH_AVX2 && !XSIMD_WITH_AVX512F
  if constexpr (std::is_same_v<T, float>) return _mm256_i32gather_ps(column, index, 4);
  else return _mm256_i32gather_epi32(reinterpret_cast<const int*>(column), index, 4);
#else
  return xsimd::batch<T>::gather(column, index);
#endif
}

}  // namespace erpt
