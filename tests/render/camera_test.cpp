// The pinhole camera follows Mitsuba's conventions: projection and ray generation invert
// each other, the image is not mirrored, and every fov axis converts correctly.
#include <gtest/gtest.h>

#include "erpt/camera.h"
#include "erpt/rng.h"

namespace erpt {
namespace {

CameraSettings lookingDownMinusZ(float fov, FovAxis axis) {
  CameraSettings s;
  s.toWorld = Transform::lookAt(Vec3(0, 1, 6.8f), Vec3(0, 1, 0), Vec3(0, 1, 0));
  s.fovDegrees = fov;
  s.fovAxis = axis;
  return s;
}

TEST(Camera, ProjectThenGenerateHitsThePoint) {
  Camera cam(lookingDownMinusZ(30, FovAxis::X), 320, 200);
  for (uint32_t i = 0; i < 200; ++i) {
    Vec3 p{uniformFloat(i, 0) * 2 - 1, uniformFloat(i, 1) * 2, uniformFloat(i, 2) * 2 - 1};
    float fx, fy;
    ASSERT_TRUE(cam.project(p, fx, fy));
    Camera::Ray r = cam.generateRay(fx, fy);
    Vec3 toPoint = normalize(p - r.origin);
    EXPECT_GT(dot(toPoint, r.direction), 1.0f - 1e-6f) << i;
  }
}

TEST(Camera, ImageOrientationMatchesMitsuba) {
  // Looking down -z with +y up, world -x appears on the image's left, +y at its top.
  Camera cam(lookingDownMinusZ(40, FovAxis::X), 100, 100);
  float fx, fy;
  ASSERT_TRUE(cam.project(Vec3(-0.5f, 1, 0), fx, fy));
  EXPECT_LT(fx, 50.0f);
  EXPECT_NEAR(fy, 50.0f, 1e-3f);
  ASSERT_TRUE(cam.project(Vec3(0, 1.5f, 0), fx, fy));
  EXPECT_LT(fy, 50.0f);
  EXPECT_FALSE(cam.project(Vec3(0, 1, 10), fx, fy));  // behind the camera
  Camera::Ray centre = cam.generateRay(50, 50);
  EXPECT_NEAR(centre.direction.z, -1.0f, 1e-6f);
}

TEST(Camera, FovAxes) {
  const int w = 400, h = 200;
  const float t = std::tan(30.0f * kPi / 180.0f);  // fov 60
  auto tanX = [&](FovAxis a) { return Camera(lookingDownMinusZ(60, a), w, h).tanHalfFovX(); };
  EXPECT_NEAR(tanX(FovAxis::X), t, 1e-6f);
  EXPECT_NEAR(tanX(FovAxis::Y), t * 2.0f, 1e-6f);
  EXPECT_NEAR(tanX(FovAxis::Diagonal), t * w / std::sqrt(float(w * w + h * h)), 1e-6f);
  EXPECT_NEAR(tanX(FovAxis::Smaller), tanX(FovAxis::Y), 1e-6f);  // height is the smaller side
  EXPECT_NEAR(tanX(FovAxis::Larger), tanX(FovAxis::X), 1e-6f);
}

TEST(Camera, FilmEdgesSpanTheFieldOfView) {
  Camera cam(lookingDownMinusZ(90, FovAxis::X), 64, 64);
  Camera::Ray left = cam.generateRay(0, 32), right = cam.generateRay(64, 32);
  // 90 degrees horizontally: the edge rays are 45 degrees off the axis on either side.
  EXPECT_NEAR(std::acos(dot(left.direction, right.direction)), kPi / 2, 1e-5f);
  EXPECT_LT(left.direction.x, 0.0f);
}

}  // namespace
}  // namespace erpt

namespace erpt {
namespace {

// The SIMD batch path gives the same rays as the scalar one (including the scalar tail).
TEST(Camera, BatchedRaysMatchScalarRays) {
  CameraSettings s = lookingDownMinusZ(35, FovAxis::X);
  s.toWorld = s.toWorld * Transform::scale(1, 2, 1);  // a scaled frame: directions need normalizing
  s.nearClip = 0.1f;
  s.farClip = 50.0f;
  Camera cam(s, 64, 48);
  const size_t n = 37;
  std::vector<float> fx(n), fy(n), dx(n), dy(n), dz(n), tn(n), tf(n);
  for (size_t i = 0; i < n; ++i) {
    fx[i] = 64 * uniformFloat(i, 5);
    fy[i] = 48 * uniformFloat(i, 6);
  }
  cam.generateRays(fx.data(), fy.data(), n, dx.data(), dy.data(), dz.data(), tn.data(), tf.data());
  for (size_t i = 0; i < n; ++i) {
    Camera::Ray r = cam.generateRay(fx[i], fy[i]);
    EXPECT_NEAR(dx[i], r.direction.x, 1e-6f) << i;
    EXPECT_NEAR(dy[i], r.direction.y, 1e-6f) << i;
    EXPECT_NEAR(dz[i], r.direction.z, 1e-6f) << i;
    EXPECT_NEAR(tn[i], r.tnear, 1e-6f) << i;
    EXPECT_NEAR(tf[i], r.tfar, 1e-3f) << i;
  }
}

}  // namespace
}  // namespace erpt
