// Textures by <ref>: wherever Mitsuba takes a texture (a named parameter, a scale texture's
// nested texture, a bump or normal map's heights), a reference to one defined elsewhere.
#include <gtest/gtest.h>

#include "erpt/render.h"
#include "erpt/scene_loader.h"
#include "support/image_stats.h"
#include "support/test_support.h"

namespace erpt {
namespace {

// The checkerboard of tests/data/texture-reference.xml: Mitsuba's 2x2 checks per unit uv
// square, uscale = vscale = 4, colour0 where the check indices sum to an even number.
Color checks(float u, float v) {
  const bool even = (int(std::floor(8 * u)) + int(std::floor(8 * v))) % 2 == 0;
  return even ? Color(0.8f, 0.6f, 0.4f) : Color(0.2f);
}

TEST(TextureReference, ScaleAndParametersTakeAReferencedTexture) {
  const Scene s = loadScene(test::sourceDir() + "/tests/data/texture-reference.xml");
  EXPECT_TRUE(s.warnings.messages.empty()) << s.warnings.messages.front();
  const int floor = s.mesh.material[s.shapes[0].firstTriangle];
  const int cube = s.mesh.material[s.shapes[1].firstTriangle];
  for (float u : {0.05f, 0.2f, 0.6f, 0.9f})
    for (float v : {0.05f, 0.2f}) {
      const Color floorColor = s.surfaceColors(floor, u, v).reflectance;
      const Color cubeColor = s.surfaceColors(cube, u, v).reflectance;
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(floorColor[c], 0.5f * checks(u, v)[c], 1e-6f) << u << " " << v;
        EXPECT_NEAR(cubeColor[c], checks(u, v)[c], 1e-6f) << u << " " << v;
      }
    }
  // The bump map's heights: the referenced checkerboard scaled by 0.01.
  const Material& bumpy = s.materials[size_t(cube)];
  ASSERT_EQ(bumpy.shadingMap, ShadingMap::Bump);
  const Texture& heights = s.textures[size_t(bumpy.shadingTexture)];
  EXPECT_NEAR(heights.color0.x, 0.008f, 1e-7f);
  EXPECT_NEAR(heights.color1.x, 0.002f, 1e-7f);
}

TEST(TextureReference, SceneRendersWithThePathTracer) {
  const Scene s = loadScene(test::sourceDir() + "/tests/data/texture-reference.xml");
  RenderSettings settings;
  settings.integrator = "path";
  settings.spp = 16;
  settings.seed = 3;
  RenderStats stats;
  const RgbImage img = render(s, settings, stats);
  EXPECT_EQ(stats.invalidSamples, 0u);
  const Color mean = test::meanOf(img);
  EXPECT_GT(mean.y, 0.01f);
  EXPECT_TRUE(std::isfinite(mean.x) && std::isfinite(mean.y) && std::isfinite(mean.z));
}

// Mitsuba 0.6's scale also scales a constant `value`, by a colour; a reference to an unknown
// id is an error at its own line.
TEST(TextureReference, ScaleOfAConstantByAColourAndUnknownIdsAreErrors) {
  test::TempDir dir;
  const Scene s = loadScene(dir.write("s.xml", R"(<scene version="0.6.0"><shape type="rectangle"><bsdf type="diffuse">
      <texture type="scale" name="reflectance"><rgb name="value" value="0.5"/><rgb name="scale" value="1, 0.5, 0.25"/></texture>
    </bsdf></shape></scene>)"));
  const Color c = s.surfaceColors(s.mesh.material[0], 0.3f, 0.3f).reflectance;
  EXPECT_FLOAT_EQ(c.x, 0.5f);
  EXPECT_FLOAT_EQ(c.y, 0.25f);
  EXPECT_FLOAT_EQ(c.z, 0.125f);
  const std::string bad = dir.write("bad.xml", "<scene version=\"0.6.0\"><shape type=\"rectangle\"><bsdf type=\"diffuse\">\n"
                                               "<texture type=\"scale\" name=\"reflectance\">\n"
                                               "<ref id=\"nowhere\"/></texture></bsdf></shape></scene>");
  try {
    loadScene(bad);
    ADD_FAILURE() << "no error for a reference to an unknown texture";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(bad + ":3: error: reference to unknown texture id 'nowhere'"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace erpt
