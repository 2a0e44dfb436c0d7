// Camera ray directions for whole arrays of film positions, vectorized with xsimd (AVX2
// lanes: lane_arch.h). Same math as Camera::generateRay.
#include <xsimd/xsimd.hpp>

#include "kernels/lane_arch.h"
#include "kernels/lane_batches.h"
#include "models/camera.h"

namespace erpt {

void Camera::generateRays(const float* filmX, const float* filmY, size_t n, float* dirX, float* dirY, float* dirZ,
                          float* tnear, float* tfar) const {
  using batch = LaneBatch<float>;
  constexpr size_t lanes = batch::size;
  const batch scaleX(-2.0f / float(width_)), scaleY(-2.0f / (float(height_) * aspect_));
  const batch offsetY(1.0f / aspect_), t(tanHalfX_), one(1.0f), nearB(nearClip_), farB(farClip_);
  const float* m = rotation_;
  forEachLaneBatch<lanes>(n, std::array<const float*, 2>{filmX, filmY},
                          std::array<float*, 5>{dirX, dirY, dirZ, tnear, tfar},
                          [&](const std::array<const float*, 2>& in, const std::array<float*, 5>& out) {
    // Camera space: x to the image's left, y up, z forward (see generateRay).
    batch u = xsimd::fma(batch::load_unaligned(in[0]), scaleX, one);
    batch v = xsimd::fma(batch::load_unaligned(in[1]), scaleY, offsetY);
    batch lx = u * t, ly = v * t;
    batch localLength = xsimd::sqrt(lx * lx + ly * ly + one);  // local.z = 1 before normalizing
    batch wx = m[0] * lx + m[1] * ly + batch(m[2]);
    batch wy = m[3] * lx + m[4] * ly + batch(m[5]);
    batch wz = m[6] * lx + m[7] * ly + batch(m[8]);
    batch inv = one / xsimd::sqrt(wx * wx + wy * wy + wz * wz);
    (wx * inv).store_unaligned(out[0]);
    (wy * inv).store_unaligned(out[1]);
    (wz * inv).store_unaligned(out[2]);
    (nearB * localLength).store_unaligned(out[3]);
    (farB * localLength).store_unaligned(out[4]);
  });
}

}  // namespace erpt
