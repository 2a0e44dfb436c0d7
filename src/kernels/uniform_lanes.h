// uniformFloat (core/rng.h) for many streams at once: the same SplitMix64 bits, hence the same
// numbers, four 64-bit lanes per AVX2 instruction. A shade kernel draws several numbers per
// path; one at a time, each is a dependent chain of two 64-bit multiplies.
#pragma once

#include <cstddef>
#include <cstdint>

namespace erpt {

// out[j] = uniformFloat(key, dim) for offset[j] = dimensionOffset(key, dim) (core/rng.h), j < n.
void uniformFloatsAt(const uint64_t* offset, size_t n, float* out);

}  // namespace erpt
