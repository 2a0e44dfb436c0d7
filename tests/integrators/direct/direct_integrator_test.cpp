// The direct-lighting integrator against closed-form answers, and determinism.
#include <gtest/gtest.h>

#include "models/camera.h"
#include "erpt/render.h"
#include "erpt/scene_loader.h"
#include "support/image_stats.h"
#include "support/test_support.h"

namespace erpt {
namespace {

using test::TempDir;

using test::meanOf;

// The camera sits inside a sphere whose inner side emits Le and reflects diffusely with
// albedo a. Direct lighting sees Le plus one bounce of the enclosure's emission:
// irradiance pi*Le, reflected radiance a*Le, so L = Le * (1 + a) at every pixel.
std::string furnaceScene(const char* bsdf) {
  return std::string(R"(<scene version="3.0.0">
    <sensor type="perspective"><float name="fov" value="60"/>
      <transform name="to_world"><lookat origin="0.2,0.1,0" target="1,0.3,0.2" up="0,1,0"/></transform>
      <film type="hdrfilm"><integer name="width" value="24"/><integer name="height" value="16"/></film></sensor>
    <shape type="sphere"><boolean name="flip_normals" value="true"/>)") +
         bsdf + R"(
      <emitter type="area"><rgb name="radiance" value="1, 0.5, 2"/></emitter></shape>
  </scene>)";
}

TEST(StatisticalDirect, FurnaceSphereMatchesClosedForm) {
  TempDir dir;
  Scene scene = loadScene(dir.write("s.xml", furnaceScene(R"(<bsdf type="diffuse"><rgb name="reflectance" value="0.5, 0.8, 0.3"/></bsdf>)")));
  RenderSettings s;
  s.integrator = "direct";
  s.spp = 64;
  s.seed = 3;
  RenderStats stats;
  Color mean = meanOf(render(scene, s, stats));
  EXPECT_NEAR(mean.x, 1.0f * 1.5f, 0.01f * 1.5f);
  EXPECT_NEAR(mean.y, 0.5f * 1.8f, 0.01f * 0.9f);
  EXPECT_NEAR(mean.z, 2.0f * 1.3f, 0.01f * 2.6f);
  EXPECT_EQ(stats.invalidSamples, 0u);
}

// A camera looking straight down from (0, 0, 3) at a diffuse plane (albedo 0.6) at z = 0,
// box filter; `extra` adds the lights (and any occluders).
std::string planeScene(int fovDegrees, int size, const std::string& extra) {
  const std::string n = std::to_string(size);
  return R"(<scene version="3.0.0">
    <sensor type="perspective"><float name="fov" value=")" + std::to_string(fovDegrees) + R"("/>
      <transform name="to_world"><lookat origin="0,0,3" target="0,0,0" up="0,1,0"/></transform>
      <film type="hdrfilm"><integer name="width" value=")" + n + R"("/><integer name="height" value=")" + n + R"("/>
        <rfilter type="box"/></film></sensor>
    <shape type="rectangle"><transform name="to_world"><scale value="4"/></transform>
      <bsdf type="diffuse"><rgb name="reflectance" value="0.6"/></bsdf></shape>)" + extra + "</scene>";
}

TEST(Direct, PointLightOverDiffusePlaneMatchesInverseSquareLaw) {
  // Camera above a diffuse plane (albedo a) lit by a point light of intensity I at height h:
  // L(p) = a/pi * I * cos(theta) / d^2 with cos(theta) = h / d. Next-event estimation of a
  // point light has no noise, so each pixel must match to within the pixel footprint.
  TempDir dir;
  const float a = 0.6f, I = 5.0f, h = 1.0f;
  Scene scene = loadScene(dir.write("s.xml", planeScene(50, 32, R"(
    <emitter type="point"><point name="position" value="0.3, -0.2, 1"/><rgb name="intensity" value="5"/></emitter>)")));
  RenderSettings s;
  s.integrator = "direct";
  s.spp = 16;
  RenderStats stats;
  RgbImage img = render(scene, s, stats);
  Camera cam(scene.camera, 32, 32);
  int checked = 0;
  for (int y = 4; y < 28; y += 3)
    for (int x = 4; x < 28; x += 3) {
      Camera::Ray r = cam.generateRay(x + 0.5f, y + 0.5f);
      Vec3 p = r.origin + r.direction * (-r.origin.z / r.direction.z);
      Vec3 d = Vec3(0.3f, -0.2f, h) - p;
      float dist2 = dot(d, d);
      float expected = a / kPi * I * (h / std::sqrt(dist2)) / dist2;
      EXPECT_NEAR(img.at(x, y).y, expected, 0.01f * expected) << x << "," << y;
      ++checked;
    }
  EXPECT_EQ(checked, 64);
}

// Mitsuba's spot: full intensity within beam_width of its axis, linear in angle down to 0 at
// cutoff_angle. Camera above a diffuse plane, spot at height h pointing straight down: each
// pixel is the point-light law times the falloff at its angle off the axis (noise-free NEE).
TEST(Direct, SpotLightFollowsItsFalloffCurve) {
  TempDir dir;
  const float a = 0.6f, I = 5.0f, h = 1.0f, cutoff = 45, beam = 25;
  Scene scene = loadScene(dir.write("s.xml", planeScene(60, 96, R"(
    <emitter type="spot"><rgb name="intensity" value="5"/><float name="cutoff_angle" value="45"/>
      <float name="beam_width" value="25"/>
      <transform name="to_world"><lookat origin="0.1, -0.2, 1" target="0.1, -0.2, 0" up="0,1,0"/></transform></emitter>)")));
  RenderSettings s;
  s.integrator = "direct";
  s.spp = 16;
  RenderStats stats;
  RgbImage img = render(scene, s, stats);
  Camera cam(scene.camera, 96, 96);
  int inBeam = 0, inBand = 0, outside = 0;
  for (int y = 1; y < 95; y += 3)
    for (int x = 1; x < 95; x += 3) {
      Camera::Ray r = cam.generateRay(x + 0.5f, y + 0.5f);
      Vec3 p = r.origin + r.direction * (-r.origin.z / r.direction.z);
      Vec3 d = Vec3(0.1f, -0.2f, h) - p;
      float dist2 = dot(d, d), dist = std::sqrt(dist2);
      float angle = std::acos(h / dist) * 180 / kPi;  // off the (downward) axis
      // Pixels whose footprint (about 1 degree here) straddles a kink of the curve are skipped;
      // elsewhere the pixel average of the smooth law matches its centre value to ~0.5%.
      if (std::abs(angle - beam) < 2.0f || std::abs(angle - cutoff) < 2.0f) continue;
      float falloff = angle <= beam ? 1.0f : angle >= cutoff ? 0.0f : (cutoff - angle) / (cutoff - beam);
      float expected = a / kPi * I * falloff * (h / dist) / dist2;
      EXPECT_NEAR(img.at(x, y).y, expected, 0.01f * expected + 1e-6f) << x << "," << y << " angle " << angle;
      (falloff == 1 ? inBeam : falloff == 0 ? outside : inBand)++;
    }
  EXPECT_GT(inBeam, 20);
  EXPECT_GT(inBand, 20);
  EXPECT_GT(outside, 20);
}

// A directional light of irradiance E (normal incidence) arriving at angle theta on a diffuse
// plane of albedo a: L = a / pi * E cos(theta) at every lit pixel; a box casts a shadow
// (next-event rays towards the light are blocked), for both integrators that do NEE.
TEST(Direct, DirectionalLightGivesUniformLambertShading) {
  TempDir dir;
  Scene scene = loadScene(dir.write("s.xml", planeScene(50, 32, R"(
    <shape type="cube"><transform name="to_world"><scale value="0.2"/><translate x="-0.6" y="0.6" z="0.5"/></transform></shape>
    <emitter type="directional"><rgb name="irradiance" value="3"/><vector name="direction" value="0.6, 0, -0.8"/></emitter>)")));
  const float expected = 0.6f / kPi * 3.0f * 0.8f;
  for (const char* integrator : {"direct", "path"}) {
    RenderSettings s;
    s.integrator = integrator;
    s.spp = 16;
    s.maxDepth = 2;
    RenderStats stats;
    const RgbImage img = render(scene, s, stats);
    int lit = 0, shadowed = 0;
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 32; ++x) {
        const float v = img.at(x, y).y;
        if (std::abs(v - expected) < 1e-3f * expected) ++lit;
        if (v < 1e-6f) ++shadowed;
      }
    EXPECT_GT(lit, 32 * 32 * 3 / 4) << integrator;  // all but the box and its shadow
    EXPECT_GT(shadowed, 10) << integrator;
  }
}

TEST(Direct, SameSeedSameImageForAnyThreadCount) {
  Scene scene = loadScene(test::sourceDir() + "/scenes/default/scene.xml");
  RenderSettings s;
  s.integrator = "direct";
  s.width = 48;
  s.height = 48;
  s.spp = 4;
  s.seed = 11;
  RenderStats a, b;
  s.threads = 1;
  RgbImage one = render(scene, s, a);
  s.threads = 2;
  RgbImage two = render(scene, s, b);
  ASSERT_EQ(one.pixels.size(), two.pixels.size());
  for (size_t i = 0; i < one.pixels.size(); ++i) {
    ASSERT_EQ(one.pixels[i].x, two.pixels[i].x) << i;
    ASSERT_EQ(one.pixels[i].y, two.pixels[i].y) << i;
    ASSERT_EQ(one.pixels[i].z, two.pixels[i].z) << i;
  }
  s.seed = 12;
  RgbImage other = render(scene, s, b);
  EXPECT_NE(meanOf(other).x, meanOf(one).x);  // the seed matters
}

}  // namespace
}  // namespace erpt
