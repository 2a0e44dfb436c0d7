// Instanced triangles (scene.h's InstanceSet): which instance a primitive id belongs to, and
// the world-space geometry of its prototype triangle.
#include <algorithm>

#include "models/surface.h"

namespace erpt {

uint32_t InstanceSet::instanceOf(uint32_t primitive) const {
  // firstPrimitive rises with k; the instance is the last one starting at or before it.
  const auto after = std::upper_bound(firstPrimitive.begin(), firstPrimitive.end(), primitive);
  return uint32_t(after - firstPrimitive.begin()) - 1;
}

uint64_t InstanceSet::instancedTriangleCount() const {
  uint64_t total = 0;
  for (uint32_t g : group) total += groupTriangleCount[g];
  return total;
}

SurfacePoint instanceSurfaceAt(const Scene& scene, uint32_t primitive, float b1, float b2) {
  const InstanceSet& in = scene.instances;
  const uint32_t k = in.instanceOf(primitive);
  const uint32_t t = in.prototypeTriangle(k, primitive);
  SurfacePoint sp = triangleSurfaceAt(in.prototypes, t, b1, b2);
  // The winding's normal of the placed triangle: the transformed face normal, turned when
  // to_world mirrors (as the copied triangle's cross product would turn).
  const Vec3 ng = normalize(in.normalToWorld[k].vector(sp.geometricNormal));
  sp.position = in.toWorld[k].point(sp.position);
  sp.geometricNormal = in.mirrored[k] ? -ng : ng;
  // Vertex normals transform as normals and keep their side; a flat triangle shades with
  // its (placed) face normal.
  sp.shading = Frame(in.prototypes.smooth[t] ? normalize(in.normalToWorld[k].vector(sp.shading.n)) : sp.geometricNormal);
  sp.primitive = primitive;
  return sp;
}

float Scene::primitiveArea(uint32_t primitive) const {
  if (primitive < mesh.triangleCount()) return 0.5f * length(mesh.faceNormal(primitive));
  if (isSphere(primitive)) return spheres.area(sphereOf(primitive));
  const uint32_t k = instances.instanceOf(primitive);
  const TriangleSoup& m = instances.prototypes;
  const uint32_t t = instances.prototypeTriangle(k, primitive);
  const Transform& toWorld = instances.toWorld[k];
  const Vec3 a = toWorld.point(m.position(m.v0[t]));
  return 0.5f * length(cross(toWorld.point(m.position(m.v1[t])) - a, toWorld.point(m.position(m.v2[t])) - a));
}

}  // namespace erpt
