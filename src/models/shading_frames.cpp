// Shading frames that surfaceAt adjusts: normal and bump mapping, as Mitsuba defines them,
// and frames whose tangent s follows dp/du (anisotropic roughness: alpha_u lies along dp/du).
// Only the shading frame changes (the geometric normal, and so emission, ray offsets and the
// light sampler, stay), in every integrator alike: the path tracer shades with it, and ERPT's
// path vertices store the frame's normal and tangent, so chains evaluate the same BSDF the
// seeds saw.
//  - normalmap (Mitsuba 3): the texture's RGB in [0, 1] is a normal 2 rgb - 1 in the tangent
//    frame (s = dp/du made orthogonal to the shading normal n, t = n x s, n).
//  - bumpmap (Mitsuba 0.6 and 3): the texture is a height h (its luminance, times `scale`);
//    the surface is displaced along n, so dp/du gains n dh/du and dp/dv gains n dh/dv, and the
//    normal is their cross product (the derivative of n itself is neglected, as Mitsuba does),
//    turned to the side of the unperturbed shading normal.
#include <cmath>

#include "models/surface.h"

namespace erpt {

bool triangleUvDerivatives(const TriangleSoup& m, uint32_t tri, Vec3& dpdu, Vec3& dpdv) {
  const uint32_t i0 = m.v0[tri], i1 = m.v1[tri], i2 = m.v2[tri];
  const float du1 = m.u[i1] - m.u[i0], dv1 = m.v[i1] - m.v[i0];
  const float du2 = m.u[i2] - m.u[i0], dv2 = m.v[i2] - m.v[i0];
  const Vec3 dp1 = m.position(i1) - m.position(i0), dp2 = m.position(i2) - m.position(i0);
  const float det = du1 * dv2 - dv1 * du2;
  if (!(std::abs(det) > 1e-20f)) return false;
  const float inv = 1 / det;
  dpdu = (dp1 * dv2 - dp2 * dv1) * inv;
  dpdv = (dp2 * du1 - dp1 * du2) * inv;
  return true;
}

namespace {

Vec3 mappedNormal(const Scene& scene, const Material& m, const SurfacePoint& sp) {
  const Texture& texture = scene.textures[size_t(m.shadingTexture)];
  const Vec3 n = sp.shading.n;
  Vec3 dpdu, dpdv;
  if (!triangleUvDerivatives(scene.mesh, sp.primitive, dpdu, dpdv)) dpdu = sp.shading.s, dpdv = sp.shading.t;
  if (m.shadingMap == ShadingMap::Normal) {
    const Color c = texture.eval(sp.u, sp.v);
    Vec3 s = dpdu - n * dot(n, dpdu);
    const float len = length(s);
    s = len > 0 ? s / len : sp.shading.s;
    const Vec3 t = cross(n, s);
    return s * (2 * c.x - 1) + t * (2 * c.y - 1) + n * (2 * c.z - 1);
  }
  float hu, hv;
  texture.luminanceGradient(sp.u, sp.v, hu, hv);
  const Vec3 pu = dpdu + n * (hu * m.bumpScale - dot(n, dpdu));
  const Vec3 pv = dpdv + n * (hv * m.bumpScale - dot(n, dpdv));
  const Vec3 bumped = cross(pu, pv);
  return dot(bumped, n) < 0 ? -bumped : bumped;
}

}  // namespace

void adjustShadingFrame(const Scene& scene, SurfacePoint& sp) {
  const Material& m = scene.materials[size_t(sp.material)];
  Vec3 n = sp.shading.n;
  if (m.shadingMap != ShadingMap::None) {
    const Vec3 mapped = mappedNormal(scene, m, sp);
    const float len = length(mapped);
    // A texel of (0.5, 0.5, 0.5), or a degenerate bump, gives no direction: keep the normal.
    if (len > 1e-12f && std::isfinite(len)) n = mapped / len;
  }
  // The tangent along dp/du, where the triangle's uvs give one; else the frame n alone gives.
  Vec3 dpdu, dpdv;
  if (triangleUvDerivatives(scene.mesh, sp.primitive, dpdu, dpdv)) {
    const Vec3 s = dpdu - n * dot(n, dpdu);
    const float len = length(s);
    if (len > 1e-12f * length(dpdu) && std::isfinite(len)) {
      sp.shading = Frame(n, s / len);
      return;
    }
  }
  sp.shading = Frame(n);
}

}  // namespace erpt
