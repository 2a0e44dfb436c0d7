// The tracer's sphere coordinates in vector lanes agree with sphereCoordinates (the scalar
// definition, models/surface.h) for any count, including the tail that does not fill a
// vector, over random directions and the places where atan2 is delicate: the poles, the seam
// where the azimuth wraps from 2 pi to 0, and signed zeros.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "kernels/sphere_coordinates.h"
#include "models/surface.h"

namespace erpt {
namespace {

SphereSet unitSphere() {
  SphereSet s;
  s.cx = {0.5f}, s.cy = {-2.0f}, s.cz = {3.0f}, s.radius = {1.5f};
  s.frame = {Frame(normalize(Vec3(0.3f, -0.2f, 0.9f)))};
  s.material = {0}, s.emitter = {-1}, s.shape = {0}, s.flipped = {0};
  return s;
}

std::vector<Vec3> testDirections() {
  std::vector<Vec3> d = {{0, 0, 1},  {0, 0, -1}, {1, 0, 0},      {-1, 0, 0},     {-1, -0.0f, 0}, {-1, 1e-9f, 0},
                         {1, -1e-9f, 0}, {1, -0.0f, 0}, {1e-8f, 0, 1}, {0, 1e-8f, -1}, {0, 1, 0},      {0, -1, 0}};
  std::mt19937 rng(7);
  std::normal_distribution<float> g;
  while (d.size() < 1000) {
    const Vec3 v(g(rng), g(rng), g(rng));
    if (length(v) > 1e-3f) d.push_back(normalize(v));
  }
  return d;
}

TEST(SphereCoordinatesInLanes, AgreeWithTheScalarDefinition) {
  const SphereSet s = unitSphere();
  const std::vector<Vec3> dirs = testDirections();
  for (size_t n : {size_t(0), size_t(1), size_t(7), size_t(9), size_t(31), dirs.size()}) {
    std::vector<float> x(n), y(n), z(n), u(n + 1, -1.0f), v(n + 1, -1.0f);
    std::vector<float> su(n), sv(n);
    for (size_t j = 0; j < n; ++j) {
      const Vec3 p = s.center(0) + s.frame[0].toWorld(dirs[j]) * s.radius[0];
      sphereCoordinates(s, 0, p, su[j], sv[j]);
      const Vec3 local = s.frame[0].toLocal(p - s.center(0));
      x[j] = local.x, y[j] = local.y, z[j] = local.z;
    }
    sphereCoordinatesOf(x.data(), y.data(), z.data(), n, u.data(), v.data());
    for (size_t j = 0; j < n; ++j) {
      // A few float ulps of a value in [0, 1]; the azimuth's seam wraps to the same side.
      EXPECT_NEAR(u[j], su[j], 4e-7f) << "n " << n << ", direction " << j;
      EXPECT_NEAR(v[j], sv[j], 4e-7f) << "n " << n << ", direction " << j;
      EXPECT_GE(u[j], 0.0f);
      EXPECT_LT(u[j], 1.0f);
      EXPECT_GE(v[j], 0.0f);
      EXPECT_LE(v[j], 1.0f);
    }
    EXPECT_EQ(u[n], -1.0f) << "wrote past n = " << n;
    EXPECT_EQ(v[n], -1.0f) << "wrote past n = " << n;
  }
}

}  // namespace
}  // namespace erpt
