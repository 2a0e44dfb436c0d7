#include "kernels/sphere_coordinates.h"

#include <algorithm>

#include <xsimd/xsimd.hpp>

#include "erpt/math.h"

namespace erpt {

void sphereCoordinatesOf(const float* x, const float* y, const float* z, size_t n, float* u, float* v) {
  using batch = xsimd::batch<float>;
  constexpr size_t lanes = batch::size;
  const batch twoPi(2 * kPi), halfInvPi(0.5f * kInvPi), invPi(kInvPi), largestBelowOne(0x1.fffffep-1f);
  // One batch: all pointers have `lanes` readable/writable floats.
  auto coordinates = [&](const float* px, const float* py, const float* pz, float* pu, float* pv) {
    const batch lx = batch::load_unaligned(px), ly = batch::load_unaligned(py), lz = batch::load_unaligned(pz);
    batch phi = xsimd::atan2(ly, lx);
    phi = xsimd::select(phi < batch(0.0f), phi + twoPi, phi);
    xsimd::min(phi * halfInvPi, largestBelowOne).store_unaligned(pu);
    // atan2 for the polar angle too: acos loses half the digits near the poles.
    (xsimd::atan2(xsimd::sqrt(lx * lx + ly * ly), lz) * invPi).store_unaligned(pv);
  };
  size_t i = 0;
  for (; i + lanes <= n; i += lanes) coordinates(x + i, y + i, z + i, u + i, v + i);
  if (i == n) return;
  // The tail through the same code on padded copies, so every hit gets identical math.
  float in[3][lanes] = {}, out[2][lanes];
  const size_t rest = n - i;
  std::copy(x + i, x + n, in[0]);
  std::copy(y + i, y + n, in[1]);
  std::copy(z + i, z + n, in[2]);
  coordinates(in[0], in[1], in[2], out[0], out[1]);
  std::copy(out[0], out[0] + rest, u + i);
  std::copy(out[1], out[1] + rest, v + i);
}

}  // namespace erpt
