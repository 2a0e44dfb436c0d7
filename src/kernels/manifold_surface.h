// The manifold walk's view of a scene's surface point (kernels/manifold_walk.h): position,
// tangents and how the shading normal turns, from the shapes themselves. An exact sphere's
// normal turns by dp / r; a mesh's interpolated vertex normals give its triangles a curvature
// of their own (docs/manifold.md, "Curvature"), and a flat-shaded triangle has none.
#pragma once

#include <cstdint>

#include "erpt/scene.h"
#include "kernels/manifold_walk.h"

namespace erpt {

// The point of triangle `tri` at barycentrics (b1, b2) (weights of its second and third
// vertex): dpdu, dpdv are its edges from the first vertex, along which b1 and b2 grow.
ManifoldVertex manifoldTriangleVertex(const TriangleSoup& mesh, uint32_t tri, double b1, double b2);

// The point `p` of exact sphere `i` (projected onto it), its normal outwards unless the
// sphere is flipped.
ManifoldVertex manifoldSphereVertex(const SphereSet& spheres, uint32_t i, DVec3 p);
inline ManifoldVertex manifoldSphereVertex(const SphereSet& spheres, uint32_t i, Vec3 p) {
  return manifoldSphereVertex(spheres, i, DVec3{p.x, p.y, p.z});
}

}  // namespace erpt
