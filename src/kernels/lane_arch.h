// The instruction set of every xsimd kernel's batches: AVX2 with FMA (8 float lanes) whenever
// the compiler may use it, also in a build for a machine with AVX-512 (ERPT_NATIVE). The
// kernels' gathers and masks are written for 8 lanes; xsimd 8's AVX-512 batches fall back to
// per-lane loops for gathers and for masks built from values, which made a native build's
// path tracer 2x slower (docs/performance.md, "Compiled for the machine").
#pragma once

#include <xsimd/xsimd.hpp>

namespace erpt {

#if XSIMD_WITH_FMA3_AVX2
using LaneArch = xsimd::fma3<xsimd::avx2>;
#else
using LaneArch = xsimd::default_arch;
#endif

template <class T>
using LaneBatch = xsimd::batch<T, LaneArch>;

}  // namespace erpt
