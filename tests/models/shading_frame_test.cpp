// Shading frames that surfaceAt adjusts: normalmap and bumpmap (the perturbed shading normal
// against closed forms, the same shading in the path tracer and direct lighting, both
// dialects) and anisotropic roughness (the frame's tangent along dp/du).
#include <gtest/gtest.h>

#include <cmath>

#include "erpt/render.h"
#include "erpt/scene_loader.h"
#include "models/surface.h"
#include "support/shading_map_scene.h"
#include "support/test_support.h"

namespace erpt {
namespace {

constexpr float kPiF = 3.14159265f;

// The first triangle's surface point at barycentrics (0.3, 0.3).
SurfacePoint pointOnPlane(const Scene& scene) { return surfaceAt(scene, 0, 0.3f, 0.3f); }

RgbImage renderWith(const Scene& scene, const char* integrator) {
  RenderSettings s;
  s.integrator = integrator;
  s.spp = 4;
  s.seed = 3;
  RenderStats stats;
  return render(scene, s, stats);
}

// Every pixel of the mapped plane against albedo / pi * E * cos(theta): the scene has nothing
// else to light the plane, so the estimate has no noise.
void expectEveryPixel(const Scene& scene, float expected) {
  for (const char* integrator : {"path", "direct"}) {
    const RgbImage img = renderWith(scene, integrator);
    for (const Color& c : img.pixels) ASSERT_NEAR(c.y / expected, 1.0, 1e-4) << integrator;
  }
}

TEST(ShadingFrame, RectangleUvDerivativesAreItsEdges) {
  test::TempDir dir;
  const Scene scene = loadScene(test::writeMappedPlaneScene(dir, "%s", 0.5f, 1.0f));
  Vec3 dpdu, dpdv;
  ASSERT_TRUE(triangleUvDerivatives(scene.mesh, 0, dpdu, dpdv));
  EXPECT_NEAR(dpdu.x, 2, 1e-6);  // x = 2u - 1, y = 2v - 1
  EXPECT_NEAR(length(dpdu - Vec3(2, 0, 0)), 0, 1e-6);
  EXPECT_NEAR(length(dpdv - Vec3(0, 2, 0)), 0, 1e-6);
  EXPECT_FALSE(scene.adjustsShadingFrames);
}

TEST(ShadingFrame, NormalMapTiltsTheShadingNormalTowardsU) {
  test::TempDir dir;
  test::writeTiltNormalMap(dir, 40);
  const Scene scene = loadScene(test::writeMappedPlaneScene(dir, R"(<bsdf type="normalmap">
      <texture type="bitmap" name="normalmap"><string name="filename" value="normal.exr"/></texture>%s</bsdf>)", 0.6f, 2.0f));
  ASSERT_TRUE(scene.adjustsShadingFrames);
  EXPECT_TRUE(scene.warnings.messages.empty()) << scene.warnings.messages.front();
  const SurfacePoint sp = pointOnPlane(scene);
  const float t = 40 * kPiF / 180;
  EXPECT_NEAR(length(sp.shading.n - Vec3(std::sin(t), 0, std::cos(t))), 0, 1e-5);
  EXPECT_NEAR(length(sp.geometricNormal - Vec3(0, 0, 1)), 0, 1e-6);  // geometry is untouched
  expectEveryPixel(scene, 0.6f / kPiF * 2.0f * std::cos(t));
}

TEST(ShadingFrame, FlatMapsLeaveTheNormal) {
  test::TempDir dir;
  test::writeTiltNormalMap(dir, 0);
  test::writeRampHeights(dir, 0);
  for (const char* wrapper :
       {R"(<bsdf type="normalmap"><texture type="bitmap" name="normalmap"><string name="filename" value="normal.exr"/></texture>%s</bsdf>)",
        R"(<bsdf type="bumpmap"><texture type="bitmap"><string name="filename" value="ramp.exr"/></texture>%s</bsdf>)"}) {
    const Scene scene = loadScene(test::writeMappedPlaneScene(dir, wrapper, 0.5f, 1.0f));
    EXPECT_NEAR(length(pointOnPlane(scene).shading.n - Vec3(0, 0, 1)), 0, 1e-6) << wrapper;
  }
}

// Heights h = k u: dp/du = (2, 0, 0) gains n k s (s: the bumpmap's scale), dp/dv = (0, 2, 0),
// so the normal is (-k s, 0, 2) / |.|.
TEST(ShadingFrame, BumpRampTiltsTheNormalByItsSlope) {
  test::TempDir dir;
  test::writeRampHeights(dir, 1.5f);
  // Mitsuba 3: a named texture and `scale`.
  const Scene scene = loadScene(test::writeMappedPlaneScene(dir, R"(<bsdf type="bumpmap">
      <texture type="bitmap" name="arbitrary"><string name="filename" value="ramp.exr"/></texture>
      <float name="scale" value="2"/>%s</bsdf>)", 0.5f, 1.0f));
  const float ks = 1.5f * 2;
  const Vec3 expected = normalize(Vec3(-ks, 0, 2));
  EXPECT_NEAR(length(pointOnPlane(scene).shading.n - expected), 0, 1e-4);
  expectEveryPixel(scene, 0.5f / kPiF * expected.z);
  // Mitsuba 0.6: an unnamed nested texture, scaled by a `scale` texture (the same slope).
  const Scene old = loadScene(test::writeMappedPlaneScene(dir, R"(<bsdf type="bumpmap">
      <texture type="scale"><float name="scale" value="2"/>
        <texture type="bitmap"><string name="filename" value="ramp.exr"/></texture></texture>%s</bsdf>)", 0.5f, 1.0f));
  EXPECT_NEAR(length(pointOnPlane(old).shading.n - expected), 0, 1e-4);
}

TEST(ShadingFrame, MappedSphereIsTessellatedAndBadInputIsAnError) {
  test::TempDir dir;
  test::writeTiltNormalMap(dir, 10);
  const Scene sphere = loadScene(dir.write("s.xml", R"(<scene version="3.0.0"><shape type="sphere">
    <bsdf type="normalmap"><texture type="bitmap" name="normalmap"><string name="filename" value="normal.exr"/></texture>
    <bsdf type="diffuse"/></bsdf></shape></scene>)"));
  EXPECT_EQ(sphere.spheres.count(), 0u);
  ASSERT_EQ(sphere.warnings.messages.size(), 1u);
  EXPECT_NE(sphere.warnings.messages[0].find("tessellated"), std::string::npos);
  auto expectError = [&](const char* name, const std::string& bsdf, const char* cause) {
    const std::string file = dir.write(name, R"(<scene version="3.0.0"><shape type="cube">)" + bsdf + "</shape></scene>");
    try {
      loadScene(file);
      ADD_FAILURE() << "no error for " << bsdf;
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(name), std::string::npos) << message;
      EXPECT_NE(message.find(":1"), std::string::npos) << message;  // file:line
      EXPECT_NE(message.find(cause), std::string::npos) << message;
    }
  };
  expectError("a.xml", R"(<bsdf type="normalmap"><bsdf type="diffuse"/></bsdf>)", "needs a <texture>");
  expectError("b.xml", R"(<bsdf type="bumpmap"><texture type="bitmap"><string name="filename" value="normal.exr"/></texture></bsdf>)",
              "needs a nested <bsdf>");
  expectError("c.xml", R"(<bsdf type="bumpmap"><texture type="scale"/><bsdf type="diffuse"/></bsdf>)",
              "needs a nested <texture>");
}

// alpha_u lies along dp/du: the shading frame's s follows the rectangle's u axis wherever the
// shape is turned; alpha_u / alpha_v on roughplastic (isotropic, as in Mitsuba) give their mean.
TEST(ShadingFrame, AnisotropicRoughnessFollowsTheUAxis) {
  test::TempDir dir;
  const Scene scene = loadScene(dir.write("a.xml", R"(<scene version="3.0.0">
    <shape type="rectangle"><bsdf type="roughconductor"><float name="alpha_u" value="0.05"/>
      <float name="alpha_v" value="0.3"/></bsdf></shape>
    <shape type="rectangle"><transform name="to_world"><rotate z="1" angle="90"/><translate z="-1"/></transform>
      <bsdf type="roughconductor"><float name="alpha_u" value="0.05"/><float name="alpha_v" value="0.3"/></bsdf></shape>
    <shape type="rectangle"><transform name="to_world"><translate z="-2"/></transform>
      <bsdf type="roughplastic"><float name="alpha_u" value="0.1"/><float name="alpha_v" value="0.3"/></bsdf></shape>
  </scene>)"));
  ASSERT_TRUE(scene.adjustsShadingFrames);
  const Material& brushed = scene.materials[size_t(scene.mesh.material[0])];
  EXPECT_TRUE(brushed.anisotropic());
  EXPECT_FLOAT_EQ(brushed.alpha, 0.05f);
  EXPECT_FLOAT_EQ(brushed.roughnessV(), 0.3f);
  EXPECT_NEAR(length(surfaceAt(scene, 0, 0.3f, 0.3f).shading.s - Vec3(1, 0, 0)), 0, 1e-6);
  EXPECT_NEAR(length(surfaceAt(scene, 2, 0.3f, 0.3f).shading.s - Vec3(0, 1, 0)), 0, 1e-6);  // turned 90 degrees
  const Material& plastic = scene.materials[size_t(scene.mesh.material[4])];
  EXPECT_FALSE(plastic.anisotropic());
  EXPECT_FLOAT_EQ(plastic.alpha, 0.2f);
  ASSERT_EQ(scene.warnings.messages.size(), 1u);
  EXPECT_NE(scene.warnings.messages[0].find("roughplastic is isotropic"), std::string::npos);
  EXPECT_THROW(loadScene(dir.write("b.xml", R"(<scene version="3.0.0"><shape type="cube">
    <bsdf type="roughconductor"><float name="alpha_v" value="-1"/></bsdf></shape></scene>)")), InputError);
  // Mitsuba 0.6's ward: its camelCase roughness, variant and lobes; anisotropic like the above.
  const Scene ward = loadScene(dir.write("w.xml", R"(<scene version="0.6.0"><shape type="rectangle">
    <bsdf type="ward"><string name="variant" value="ward-duer"/><float name="alphaU" value="0.1"/>
      <float name="alphaV" value="0.25"/><rgb name="diffuseReflectance" value="0.2"/></bsdf></shape></scene>)"));
  const Material& w = ward.materials[size_t(ward.mesh.material[0])];
  EXPECT_EQ(w.kind, BsdfKind::Ward);
  EXPECT_EQ(w.wardVariant, WardVariant::WardDuer);
  EXPECT_TRUE(w.anisotropic());
  EXPECT_FLOAT_EQ(w.reflectance.value.x, 0.2f);
  EXPECT_FLOAT_EQ(w.specularReflectance.value.x, 0.2f);  // Mitsuba's default
  EXPECT_TRUE(ward.warnings.messages.empty()) << ward.warnings.messages.front();
  EXPECT_THROW(loadScene(dir.write("v.xml", R"(<scene version="3.0.0"><shape type="cube">
    <bsdf type="ward"><string name="variant" value="lafortune"/></bsdf></shape></scene>)")), InputError);
}

}  // namespace
}  // namespace erpt
