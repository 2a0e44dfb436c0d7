// `mask` cut-outs: the same picture as the cut geometry, in every integrator.
#include <gtest/gtest.h>

#include <cmath>

#include "erpt/render.h"
#include "erpt/scene_loader.h"
#include "support/image_stats.h"
#include "support/mask_scene.h"
#include "support/test_support.h"

namespace erpt {
namespace {

RgbImage renderWith(const Scene& scene, const char* integrator, int spp) {
  RenderSettings s;
  s.integrator = integrator;
  s.spp = spp;
  s.seed = 21;
  RenderStats stats;
  return render(scene, s, stats);
}

// Path and direct: with the same seed every ray meets the same surfaces (the squares and the
// mask's opaque checks are the same point sets), so the images agree pixel by pixel up to
// float differences at the checks' edges; without the filter the holes would be solid.
TEST(Mask, CutOutGivesTheCutGeometrysPicture) {
  test::TempDir maskDir, cutDir;
  const Scene masked = loadScene(test::writeCheckerMaskScene(maskDir, false));
  const Scene cut = loadScene(test::writeCheckerMaskScene(cutDir, true));
  ASSERT_TRUE(masked.hasMasks());
  EXPECT_TRUE(masked.warnings.messages.empty()) << masked.warnings.messages.front();
  for (const char* integrator : {"path", "direct"}) {
    const RgbImage a = renderWith(masked, integrator, 16), b = renderWith(cut, integrator, 16);
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    size_t differing = 0;
    double total = 0, difference = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
      const float la = luminance(a.pixels[i]), lb = luminance(b.pixels[i]);
      differing += std::abs(la - lb) > 0.01f * std::max(lb, 0.01f);
      total += lb, difference += std::abs(la - lb);
    }
    EXPECT_LT(differing, a.pixels.size() / 50) << integrator;  // a few edge pixels at most
    EXPECT_LT(difference, 0.01 * total) << integrator;
  }
}

TEST(Mask, PartialOpacityIsRenderedAsACutOutWithAWarning) {
  test::TempDir dir;
  const Scene s = loadScene(dir.write("s.xml", R"(<scene version="3.0.0"><shape type="cube">
    <bsdf type="mask"><float name="opacity" value="0.3"/><bsdf type="diffuse"/></bsdf></shape></scene>)"));
  ASSERT_EQ(s.warnings.messages.size(), 1u);
  EXPECT_NE(s.warnings.messages[0].find("cut-out at 0.5"), std::string::npos) << s.warnings.messages[0];
  EXPECT_FALSE(s.opaqueAt(0, 0.2f, 0.2f));  // 0.3 < 0.5: cut
  // Cut-outs filter triangles: a masked sphere is tessellated, and says so.
  const Scene sphere = loadScene(dir.write("u.xml", R"(<scene version="3.0.0"><shape type="sphere">
    <bsdf type="mask"><float name="opacity" value="1"/><bsdf type="diffuse"/></bsdf></shape></scene>)"));
  EXPECT_EQ(sphere.spheres.count(), 0u);
  EXPECT_GT(sphere.mesh.triangleCount(), 1000u);
  ASSERT_EQ(sphere.warnings.messages.size(), 1u);
  EXPECT_NE(sphere.warnings.messages[0].find("tessellated"), std::string::npos);
  // An emitter's shape is never cut, and the loader says so.
  const Scene light = loadScene(dir.write("v.xml", R"(<scene version="3.0.0"><shape type="rectangle">
    <bsdf type="mask"><float name="opacity" value="0"/><bsdf type="diffuse"/></bsdf>
    <emitter type="area"/></shape></scene>)"));
  EXPECT_TRUE(light.opaqueAt(0, 0.2f, 0.2f));
  ASSERT_EQ(light.warnings.messages.size(), 1u);
  EXPECT_NE(light.warnings.messages[0].find("not cut"), std::string::npos) << light.warnings.messages[0];
  EXPECT_THROW(loadScene(dir.write("t.xml", R"(<scene version="3.0.0"><shape type="cube">
    <bsdf type="mask"><float name="opacity" value="1"/></bsdf></shape></scene>)")), InputError);
}

}  // namespace
}  // namespace erpt
