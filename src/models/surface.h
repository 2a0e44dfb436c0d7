// The local geometry at a ray hit, reconstructed from the scene's SoA columns: a hit is a
// primitive id (scene.h) and two coordinates, barycentric for a triangle, the texture
// coordinates (azimuth / 2 pi, polar angle / pi) for a sphere, so that one (primitive, u, v)
// triple names a surface point whatever the shape.
#pragma once

#include <cmath>

#include "erpt/scene.h"

namespace erpt {

struct SurfacePoint {
  Vec3 position;
  Vec3 geometricNormal;  // unit, from the triangle's winding (emission and flip_normals follow it)
  Frame shading;         // around the interpolated shading normal (or the geometric one)
  float u = 0, v = 0;    // texture coordinates
  uint32_t primitive = 0;
  int material = 0;
  int emitter = -1;  // index into Scene::emitters when the primitive emits
};

// b1, b2: barycentric coordinates of the triangle's second and third vertex (Embree's u, v).
inline SurfacePoint triangleSurfaceAt(const TriangleSoup& m, uint32_t tri, float b1, float b2) {
  SurfacePoint s;
  uint32_t i0 = m.v0[tri], i1 = m.v1[tri], i2 = m.v2[tri];
  float b0 = 1 - b1 - b2;
  s.position = m.position(i0) * b0 + m.position(i1) * b1 + m.position(i2) * b2;
  s.geometricNormal = normalize(m.faceNormal(tri));
  Vec3 n = s.geometricNormal;
  if (m.smooth[tri]) {
    Vec3 ns = m.normal(i0) * b0 + m.normal(i1) * b1 + m.normal(i2) * b2;
    float len = length(ns);
    if (len > 0) n = ns / len;
  }
  s.shading = Frame(n);
  s.u = m.u[i0] * b0 + m.u[i1] * b1 + m.u[i2] * b2;
  s.v = m.v[i0] * b0 + m.v[i1] * b1 + m.v[i2] * b2;
  s.primitive = tri;
  s.material = m.material[tri];
  s.emitter = m.emitter[tri];
  return s;
}

// The sphere coordinates (u, v) of a point near sphere i: its direction from the centre, in
// the sphere's frame, as Mitsuba's texture coordinates. atan2 for both angles keeps the
// polar angle accurate near the poles (acos loses half the digits there). The tracer converts
// its hits in vector lanes (kernels/sphere_coordinates.h), which agree to a few ulps.
inline void sphereCoordinates(const SphereSet& s, uint32_t i, Vec3 p, float& u, float& v) {
  const Vec3 local = s.frame[i].toLocal(p - s.center(i));
  float phi = std::atan2(local.y, local.x);
  if (phi < 0) phi += 2 * kPi;
  u = std::min(phi * (0.5f * kInvPi), 0x1.fffffep-1f);
  v = std::atan2(std::sqrt(local.x * local.x + local.y * local.y), local.z) * kInvPi;
}

// The hit distance along o + t d on sphere i nearest to the tracer's estimate t, solved again
// in double precision with the closest-approach form of the discriminant (r^2 - |f|^2, f the
// centre's offset from the ray): at grazing angles float solvers lose most digits of t, and a
// point projected onto the sphere from a wrong t no longer lies on the traced ray.
inline float refineSphereHit(const SphereSet& s, uint32_t i, Vec3 o, Vec3 d, float t) {
  const double ox = double(o.x) - s.cx[i], oy = double(o.y) - s.cy[i], oz = double(o.z) - s.cz[i];
  const double a = double(d.x) * d.x + double(d.y) * d.y + double(d.z) * d.z;
  const double b = (ox * d.x + oy * d.y + oz * d.z) / a;  // closest approach at t = -b
  const double fx = ox - b * d.x, fy = oy - b * d.y, fz = oz - b * d.z;
  const double r = s.radius[i];
  const double h = std::sqrt(std::max(0.0, (r * r - (fx * fx + fy * fy + fz * fz)) / a));
  const double near = -b - h, far = -b + h;
  return float(std::abs(near - t) <= std::abs(far - t) ? near : far);
}

// The exact surface point of sphere i at sphere coordinates (u, v): position on the sphere,
// normal along the radius (inwards when flipped).
inline SurfacePoint sphereSurfaceAt(const SphereSet& s, uint32_t i, uint32_t primitive, float u, float v) {
  const float phi = u * 2 * kPi, theta = v * kPi;
  const float sinTheta = std::sin(theta);
  const Vec3 radial = s.frame[i].toWorld({sinTheta * std::cos(phi), sinTheta * std::sin(phi), std::cos(theta)});
  SurfacePoint sp;
  sp.position = s.center(i) + radial * s.radius[i];
  sp.geometricNormal = s.flipped[i] ? -radial : radial;
  sp.shading = Frame(sp.geometricNormal);
  sp.u = u;
  sp.v = v;
  sp.primitive = primitive;
  sp.material = s.material[i];
  sp.emitter = s.emitter[i];
  return sp;
}

// The derivatives dp/du and dp/dv of triangle `tri`'s position with respect to its texture
// coordinates; false when its uvs are degenerate (then any tangents of the normal serve).
bool triangleUvDerivatives(const TriangleSoup& m, uint32_t tri, Vec3& dpdu, Vec3& dpdv);
// Normal and bump mapping, and frames along dp/du (shading_frames.cpp): replaces the shading
// frame of a triangle hit by the one its material asks for.
void adjustShadingFrame(const Scene& scene, SurfacePoint& sp);

// The world-space surface point of an instanced triangle (instances.cpp): its prototype's
// point in group space, placed by the instance's to_world.
SurfacePoint instanceSurfaceAt(const Scene& scene, uint32_t primitive, float b1, float b2);

// The surface point a hit (primitive, u, v) names. (Spheres and instanced members whose
// material adjusts its shading frame are stored as world triangles when the scene loads.)
inline SurfacePoint surfaceAt(const Scene& scene, uint32_t primitive, float u, float v) {
  if (primitive >= scene.mesh.triangleCount()) {
    if (scene.isSphere(primitive)) return sphereSurfaceAt(scene.spheres, scene.sphereOf(primitive), primitive, u, v);
    return instanceSurfaceAt(scene, primitive, u, v);
  }
  SurfacePoint sp = triangleSurfaceAt(scene.mesh, primitive, u, v);
  if (scene.adjustsShadingFrames && scene.materials[size_t(sp.material)].adjustsShadingFrame())
    adjustShadingFrame(scene, sp);
  return sp;
}

// Origin for a ray leaving surface point p towards `dir`: pushed off the surface along the
// geometric normal by an amount that grows with the coordinates' magnitude (float spacing),
// so it works for both tiny and huge scenes.
inline Vec3 offsetOrigin(Vec3 p, Vec3 geometricNormal, Vec3 dir) {
  float scale = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z), 1e-2f});
  float eps = scale * 2e-5f;
  return p + geometricNormal * (dot(dir, geometricNormal) >= 0 ? eps : -eps);
}

// A shadow ray between two surface points: from `from` pushed off its surface towards `to`, to
// `to` pushed off its surface towards `from` (a zero normal: a point that is no surface, a
// point light), stopping just short of that end. Both ends are pushed, and the ray aims at the
// pushed far end: a ray that kept the direction between the unpushed points would end where the
// near end's push moved it, which can lie inside the far surface (a light seen at a grazing
// angle) and count the light as occluded by itself.
struct ShadowSegment {
  Vec3 origin, direction;
  float tfar;
};
inline ShadowSegment shadowSegment(Vec3 from, Vec3 fromNg, Vec3 to, Vec3 toNg) {
  const Vec3 d = to - from;
  const Vec3 origin = offsetOrigin(from, fromNg, d), end = offsetOrigin(to, toNg, -d);
  const Vec3 span = end - origin;
  const float length = std::sqrt(dot(span, span));
  return {origin, span / length, length * (1 - 1e-4f)};
}

}  // namespace erpt
