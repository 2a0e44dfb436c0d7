// The manifold walk's surface points from the scene's shapes (kernels/manifold_surface.h): an
// exact sphere's normal turns by dp / r, a tessellated sphere's interpolated normals turn the
// same way (to its tessellation's accuracy), and a flat-shaded triangle's does not turn.
#include <gtest/gtest.h>

#include <cmath>

#include "erpt/scene_loader.h"
#include "kernels/manifold_surface.h"
#include "support/test_support.h"

namespace erpt {
namespace {

double norm(DVec3 a) { return std::sqrt(dot(a, a)); }
DVec3 unit(DVec3 a) { return a * (1.0 / norm(a)); }
// The part of a normal's change across the tangent plane (what the constraints see).
DVec3 tangential(DVec3 dn, DVec3 n) { return dn - n * dot(dn, n); }

std::string sphereScene() { return test::sourceDir() + "/tests/data/sphere-lights.xml"; }

TEST(ManifoldSurface, AnExactSpheresNormalTurnsByItsCurvature) {
  const Scene scene = loadScene(sphereScene());
  ASSERT_GE(scene.spheres.count(), 1u);
  const uint32_t i = 0;
  const DVec3 c{scene.spheres.cx[i], scene.spheres.cy[i], scene.spheres.cz[i]};
  const double r = scene.spheres.radius[i];
  const Vec3 p = scene.spheres.center(i) + normalize(Vec3{0.3f, 0.8f, -0.5f}) * scene.spheres.radius[i];
  const ManifoldVertex v = manifoldSphereVertex(scene.spheres, i, p);
  EXPECT_NEAR(norm(v.p - c), r, 1e-6);
  EXPECT_NEAR(norm(v.n - unit(v.p - c)), 0, 1e-9);
  EXPECT_EQ(v.surface, uint32_t(scene.spheres.shape[i]));
  // Moved along each tangent and projected back onto the sphere, the normal is where
  // normalize(n + h dn) says, to second order.
  const double h = 1e-4;
  for (int axis = 0; axis < 2; ++axis) {
    const DVec3 dir = axis == 0 ? v.dpdu : v.dpdv, dn = axis == 0 ? v.dndu : v.dndv;
    const DVec3 movedNormal = unit(v.p + dir * h - c);
    EXPECT_NEAR(norm(movedNormal - unit(v.n + dn * h)), 0, 1e-7);
  }
}

TEST(ManifoldSurface, ATessellatedSphereHasTheExactSpheresCurvature) {
  LoadOptions meshed;
  meshed.tessellateSpheres = true;
  const Scene exact = loadScene(sphereScene());
  const Scene scene = loadScene(sphereScene(), meshed);
  ASSERT_EQ(scene.spheres.count(), 0u);
  const int32_t shape = exact.spheres.shape[0];
  const double r = exact.spheres.radius[0];
  int checked = 0;
  double worst = 0;
  for (uint32_t tri = 0; tri < scene.mesh.triangleCount(); ++tri) {
    if (scene.mesh.shape[tri] != shape) continue;
    ASSERT_TRUE(scene.mesh.smooth[tri]);
    const ManifoldVertex v = manifoldTriangleVertex(scene.mesh, tri, 1.0f / 3, 1.0f / 3);
    // Along each edge, the normal's tangential turn is the edge's tangential part over r.
    for (int axis = 0; axis < 2; ++axis) {
      const DVec3 dp = axis == 0 ? v.dpdu : v.dpdv, dn = axis == 0 ? v.dndu : v.dndv;
      const DVec3 expected = tangential(dp, v.n) * (1.0 / r);
      worst = std::max(worst, norm(tangential(dn, v.n) - expected) / norm(expected));
    }
    ++checked;
  }
  ASSERT_GT(checked, 100);
  EXPECT_LT(worst, 0.05);  // a tessellation's error, not a missing or doubled curvature
}

TEST(ManifoldSurface, AFlatShadedTriangleDoesNotTurn) {
  TriangleSoup mesh;
  mesh.px = {0, 1, 0}, mesh.py = {0, 0, 1}, mesh.pz = {0, 0, 0};
  mesh.nx = {0, 0, 0}, mesh.ny = {0, 0, 0}, mesh.nz = {1, 1, 1};
  mesh.v0 = {0}, mesh.v1 = {1}, mesh.v2 = {2};
  mesh.material = {0}, mesh.emitter = {-1}, mesh.shape = {4}, mesh.smooth = {0};
  const ManifoldVertex v = manifoldTriangleVertex(mesh, 0, 0.25f, 0.5f);
  EXPECT_NEAR(v.p.x, 0.25, 1e-7);
  EXPECT_NEAR(v.p.y, 0.5, 1e-7);
  EXPECT_NEAR(v.n.z, 1.0, 1e-12);
  EXPECT_EQ(norm(v.dndu) + norm(v.dndv), 0.0);
  EXPECT_EQ(v.surface, 4u);
}

}  // namespace
}  // namespace erpt
