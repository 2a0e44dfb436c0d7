// The pinhole camera follows Mitsuba's conventions: projection and ray generation invert
// each other, the image is not mirrored, and every fov axis converts correctly.
#include <gtest/gtest.h>

#include "models/camera.h"
#include "erpt/render.h"
#include "core/rng.h"
#include "erpt/scene_loader.h"
#include "support/chi_square.h"
#include "support/test_support.h"

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

namespace erpt {
namespace {

CameraSettings lensSettings(float aperture, float focus) {
  CameraSettings s;
  s.toWorld = Transform::lookAt(Vec3(1, 2, 3), Vec3(0, 0.5f, -1), Vec3(0, 1, 0));
  s.fovDegrees = 40;
  s.apertureRadius = aperture;
  s.focusDistance = focus;
  return s;
}

// Every lens ray of a film position starts on the lens disk (radius, in the plane facing
// forward) and passes through the point the pinhole ray reaches on the plane of focus.
TEST(ThinLens, RaysLeaveTheDiskAndMeetOnThePlaneOfFocus) {
  const Camera pinhole(lensSettings(0, 0), 64, 48), lens(lensSettings(0.2f, 3.0f), 64, 48);
  ASSERT_TRUE(lens.hasLens());
  ASSERT_FALSE(pinhole.hasLens());
  const Vec3 forward = normalize(lensSettings(0, 0).toWorld.vector({0, 0, 1}));
  for (int k = 0; k < 50; ++k) {
    const float fx = 64.0f * test::testUniform(k, 0), fy = 48.0f * test::testUniform(k, 1);
    const Camera::Ray p = pinhole.generateRay(fx, fy);
    const Vec3 focus = p.origin + p.direction * (3.0f / dot(p.direction, forward));
    for (int j = 0; j < 20; ++j) {
      Vec3 origin, direction = p.direction;
      float tnear, tfar;
      lens.throughLens(test::testUniform(k * 20 + j, 2), test::testUniform(k * 20 + j, 3), origin, direction, tnear, tfar);
      EXPECT_NEAR(length(direction), 1.0f, 1e-5f);
      EXPECT_LE(length(origin - p.origin), 0.2f * (1 + 1e-5f));
      EXPECT_NEAR(dot(origin - p.origin, forward), 0.0f, 1e-5f);
      const Vec3 reached = origin + direction * (3.0f / dot(direction, forward));
      EXPECT_NEAR(length(reached - focus), 0.0f, 1e-4f * length(focus - p.origin));
      EXPECT_NEAR(tnear * dot(direction, forward), lensSettings(0, 0).nearClip, 1e-6f);
    }
  }
}

// A small emitter on the axis behind the plane of focus images as its pinhole image blurred by
// a disk of radius A |1/F - 1/D| (in units of the image plane at distance 1), with the pinhole
// image's total energy; on the plane of focus it stays as sharp as through the pinhole. (Radii
// from second moments: a uniform disk of radius R has mean r^2 = R^2 / 2, and blurring adds
// second moments.)
TEST(ThinLens, DefocusBlurHasTheCircleOfConfusionsRadius) {
  auto renderAt = [](float aperture, float emitterDistance, int spp = 256) {
    test::TempDir dir;
    const std::string xml = std::string(R"(<scene version="3.0.0">
      <sensor type="thinlens"><float name="fov" value="22.62"/>
        <float name="aperture_radius" value=")") + std::to_string(aperture) + R"("/>
        <float name="focus_distance" value="2"/>
        <transform name="to_world"><lookat origin="0,0,0" target="0,0,1" up="0,1,0"/></transform>
        <film type="hdrfilm"><integer name="width" value="64"/><integer name="height" value="64"/>
          <rfilter type="box"/></film></sensor>
      <shape type="sphere"><point name="center" value="0,0,)" + std::to_string(emitterDistance) + R"("/>
        <float name="radius" value="0.05"/><emitter type="area"><rgb name="radiance" value="1000"/></emitter></shape>
    </scene>)";
    const Scene scene = loadScene(dir.write("s.xml", xml));
    RenderSettings s;
    s.integrator = "path";
    s.spp = spp;
    s.seed = 3;
    RenderStats stats;
    return render(scene, s, stats);
  };
  // Energy and the radius from the second moment: a uniform disk of radius R has mean r^2 = R^2 / 2.
  auto measure = [](const RgbImage& img, double& energy, double& radius) {
    double sum = 0, sx = 0, sy = 0, sr = 0;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        const double w = img.at(x, y).y;
        sum += w, sx += w * (x + 0.5), sy += w * (y + 0.5);
      }
    const double cx = sx / sum, cy = sy / sum;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x)
        sr += img.at(x, y).y * ((x + 0.5 - cx) * (x + 0.5 - cx) + (y + 0.5 - cy) * (y + 0.5 - cy));
    energy = sum;
    radius = std::sqrt(2 * sr / sum);
  };
  double pinholeEnergy, pinholeRadius, blurEnergy, blurRadius, focusEnergy, focusRadius;
  measure(renderAt(0, 4), pinholeEnergy, pinholeRadius);
  // Out of focus, a camera sample hits the small emitter only through part of the lens: its
  // energy is a noisy estimate (about 1.8% standard deviation at 256 spp), so it gets 1024 spp
  // (0.9%) for the 3% bound below.
  measure(renderAt(0.1f, 4, 1024), blurEnergy, blurRadius);
  measure(renderAt(0.1f, 2), focusEnergy, focusRadius);
  // tan(fov / 2) = 0.2: 160 pixels per unit of the image plane; R = 0.1 (1/2 - 1/4) = 0.025 -> 4 px.
  EXPECT_NEAR(std::sqrt(blurRadius * blurRadius - pinholeRadius * pinholeRadius), 4.0, 0.4);
  EXPECT_NEAR(pinholeRadius, 2.0, 0.3);  // the sphere itself: 0.05 / 4 -> 2 px
  EXPECT_LT(focusRadius, 4.6);            // at distance 2 the sphere is 4 px in radius, in focus
  EXPECT_NEAR(blurEnergy, pinholeEnergy, 0.03 * pinholeEnergy);
}

TEST(ThinLens, LoaderReadsThinlensAndFocalLength) {
  test::TempDir dir;
  const Scene lens = loadScene(dir.write("a.xml", R"(<scene version="0.6.0"><sensor type="thinlens">
    <float name="apertureRadius" value="0.25"/><float name="focusDistance" value="7"/>
    <string name="focalLength" value="35mm"/></sensor><shape type="cube"/></scene>)"));
  EXPECT_FLOAT_EQ(lens.camera.apertureRadius, 0.25f);
  EXPECT_FLOAT_EQ(lens.camera.focusDistance, 7.0f);
  // 35 mm equivalent: the diagonal of a 36 x 24 mm frame.
  EXPECT_NEAR(lens.camera.fovDegrees, 2 * std::atan(std::sqrt(36.0 * 36 + 24 * 24) / 70) * 180 / kPi, 1e-4);
  EXPECT_EQ(lens.camera.fovAxis, FovAxis::Diagonal);
  EXPECT_TRUE(lens.warnings.messages.empty()) << lens.warnings.messages.front();
  for (const char* bad : {R"(<sensor type="thinlens"><float name="aperture_radius" value="0.1"/></sensor>)",
                          R"(<sensor type="thinlens"><float name="focus_distance" value="-1"/></sensor>)",
                          R"(<sensor type="perspective"><string name="focal_length" value="5cm"/></sensor>)"}) {
    EXPECT_THROW(loadScene(dir.write("b.xml", std::string("<scene version=\"3.0.0\">") + bad + "<shape type=\"cube\"/></scene>")),
                 InputError)
        << bad;
  }
}

}  // namespace
}  // namespace erpt
