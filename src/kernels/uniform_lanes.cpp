// The lanes are kernels/mix64_lanes.h; builds without AVX2 take the scalar mix64.
#include "kernels/uniform_lanes.h"

#include "core/rng.h"
#include "kernels/mix64_lanes.h"

namespace erpt {

void uniformFloatsAt(const uint64_t* offset, size_t n, float* out) {
  size_t j = 0;
#if defined(__AVX2__)
  for (; j + 4 <= n; j += 4)
    _mm_storeu_ps(out + j, floatsFromBitsLanes(mix64Lanes(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(offset + j)))));
#endif
  for (; j < n; ++j) out[j] = floatFromBits(mix64(offset[j]));
}

}  // namespace erpt
