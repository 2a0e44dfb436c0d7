#include "kernels/sphere_coordinates.h"

#include <xsimd/xsimd.hpp>

#include "erpt/math.h"
#include "kernels/lane_arch.h"
#include "kernels/lane_batches.h"

namespace erpt {

void sphereCoordinatesOf(const float* x, const float* y, const float* z, size_t n, float* u, float* v) {
  using batch = LaneBatch<float>;
  constexpr size_t lanes = batch::size;
  const batch twoPi(2 * kPi), halfInvPi(0.5f * kInvPi), invPi(kInvPi), largestBelowOne(0x1.fffffep-1f);
  forEachLaneBatch<lanes>(n, std::array<const float*, 3>{x, y, z}, std::array<float*, 2>{u, v},
                          [&](const std::array<const float*, 3>& in, const std::array<float*, 2>& out) {
    const batch lx = batch::load_unaligned(in[0]), ly = batch::load_unaligned(in[1]), lz = batch::load_unaligned(in[2]);
    batch phi = xsimd::atan2(ly, lx);
    phi = xsimd::select(phi < batch(0.0f), phi + twoPi, phi);
    xsimd::min(phi * halfInvPi, largestBelowOne).store_unaligned(out[0]);
    // atan2 for the polar angle too: acos loses half the digits near the poles.
    (xsimd::atan2(xsimd::sqrt(lx * lx + ly * ly), lz) * invPi).store_unaligned(out[1]);
  });
}

}  // namespace erpt
