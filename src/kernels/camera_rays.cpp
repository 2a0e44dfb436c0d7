// Camera ray directions for whole arrays of film positions, vectorized with xsimd (the
// widest instruction set the build targets: AVX2 by default). Same math as
// Camera::generateRay.
#include <algorithm>

#include <xsimd/xsimd.hpp>

#include "models/camera.h"

namespace erpt {

void Camera::generateRays(const float* filmX, const float* filmY, size_t n, float* dirX, float* dirY, float* dirZ,
                          float* tnear, float* tfar) const {
  using batch = xsimd::batch<float>;
  constexpr size_t lanes = batch::size;
  const batch scaleX(-2.0f / float(width_)), scaleY(-2.0f / (float(height_) * aspect_));
  const batch offsetY(1.0f / aspect_), t(tanHalfX_), one(1.0f), nearB(nearClip_), farB(farClip_);
  const float* m = rotation_;
  // One batch of `lanes` rays: all pointers have `lanes` readable/writable floats.
  auto rays = [&](const float* fx, const float* fy, float* dx, float* dy, float* dz, float* tn, float* tf) {
    // Camera space: x to the image's left, y up, z forward (see generateRay).
    batch u = xsimd::fma(batch::load_unaligned(fx), scaleX, one);
    batch v = xsimd::fma(batch::load_unaligned(fy), scaleY, offsetY);
    batch lx = u * t, ly = v * t;
    batch localLength = xsimd::sqrt(lx * lx + ly * ly + one);  // local.z = 1 before normalizing
    batch wx = m[0] * lx + m[1] * ly + batch(m[2]);
    batch wy = m[3] * lx + m[4] * ly + batch(m[5]);
    batch wz = m[6] * lx + m[7] * ly + batch(m[8]);
    batch inv = one / xsimd::sqrt(wx * wx + wy * wy + wz * wz);
    (wx * inv).store_unaligned(dx);
    (wy * inv).store_unaligned(dy);
    (wz * inv).store_unaligned(dz);
    (nearB * localLength).store_unaligned(tn);
    (farB * localLength).store_unaligned(tf);
  };
  size_t i = 0;
  for (; i + lanes <= n; i += lanes)
    rays(filmX + i, filmY + i, dirX + i, dirY + i, dirZ + i, tnear + i, tfar + i);
  if (i == n) return;
  // The tail goes through the same code on padded copies, so every ray gets identical math.
  float in[2][lanes] = {}, out[5][lanes];
  const size_t rest = n - i;
  std::copy(filmX + i, filmX + n, in[0]);
  std::copy(filmY + i, filmY + n, in[1]);
  rays(in[0], in[1], out[0], out[1], out[2], out[3], out[4]);
  float* dst[5] = {dirX, dirY, dirZ, tnear, tfar};
  for (int c = 0; c < 5; ++c) std::copy(out[c], out[c] + rest, dst[c] + i);
}

}  // namespace erpt
