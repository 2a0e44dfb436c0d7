// Exterior indices of refraction: a conductor's `ext_eta` divides its eta and k (Mitsuba 0.6,
// air by default), and the dielectric-like BSDFs take `ext_ior`; both by number or by name.
#include <gtest/gtest.h>

#include "erpt/render.h"
#include "erpt/scene_loader.h"
#include "support/test_support.h"

namespace erpt {
namespace {

TEST(ExteriorIndex, ConductorEtaAndKAreRelativeToTheOutside) {
  test::TempDir dir;
  const Scene s = loadScene(dir.write("s.xml", R"(<scene version="0.6.0">
    <shape type="cube"><bsdf type="conductor"><rgb name="eta" value="1.5, 2, 2.5"/><rgb name="k" value="3"/>
      <float name="extEta" value="1.25"/></bsdf></shape>
    <shape type="cube"><bsdf type="roughconductor"><rgb name="eta" value="1.5"/><rgb name="k" value="3"/>
      <string name="ext_eta" value="Water"/></bsdf></shape>
    <shape type="cube"><bsdf type="conductor"><rgb name="eta" value="1.5"/><rgb name="k" value="3"/></bsdf></shape>
  </scene>)"));
  EXPECT_TRUE(s.warnings.messages.empty()) << s.warnings.messages.front();
  EXPECT_FLOAT_EQ(s.materials[0].eta.x, 1.5f / 1.25f);
  EXPECT_FLOAT_EQ(s.materials[0].eta.z, 2.5f / 1.25f);
  EXPECT_FLOAT_EQ(s.materials[0].k.y, 3 / 1.25f);
  EXPECT_FLOAT_EQ(s.materials[1].eta.y, 1.5f / 1.333f);
  EXPECT_FLOAT_EQ(s.materials[1].k.y, 3 / 1.333f);
  // Mitsuba 0.6's default outside is air.
  EXPECT_FLOAT_EQ(s.materials[2].eta.x, 1.5f / 1.000277f);
  // Mitsuba 3 has no exterior index: eta and k as given.
  const Scene three = loadScene(dir.write("t.xml", R"(<scene version="3.0.0">
    <shape type="cube"><bsdf type="conductor"><rgb name="eta" value="1.5"/><rgb name="k" value="3"/></bsdf></shape>
  </scene>)"));
  EXPECT_FLOAT_EQ(three.materials[0].eta.x, 1.5f);
  EXPECT_FLOAT_EQ(three.materials[0].k.x, 3.0f);
}

TEST(ExteriorIndex, DielectricsAndPlasticsTakeTheOutsideByNumberOrName) {
  test::TempDir dir;
  const Scene s = loadScene(dir.write("s.xml", R"(<scene version="0.6.0">
    <shape type="cube"><bsdf type="dielectric"><string name="intIOR" value="diamond"/><string name="extIOR" value="water"/></bsdf></shape>
    <shape type="cube"><bsdf type="roughdielectric"><float name="intIOR" value="1.6"/><float name="extIOR" value="1.2"/></bsdf></shape>
    <shape type="cube"><bsdf type="thindielectric"><float name="intIOR" value="1.6"/><string name="extIOR" value="vacuum"/></bsdf></shape>
    <shape type="cube"><bsdf type="plastic"><string name="extIOR" value="ethanol"/></bsdf></shape>
    <shape type="cube"><bsdf type="roughplastic"><float name="intIOR" value="1.7"/><float name="extIOR" value="1.1"/></bsdf></shape>
  </scene>)"));
  EXPECT_TRUE(s.warnings.messages.empty()) << s.warnings.messages.front();
  EXPECT_FLOAT_EQ(s.materials[0].relativeIOR(), 2.419f / 1.333f);
  EXPECT_FLOAT_EQ(s.materials[1].relativeIOR(), 1.6f / 1.2f);
  EXPECT_FLOAT_EQ(s.materials[2].relativeIOR(), 1.6f);
  EXPECT_FLOAT_EQ(s.materials[3].relativeIOR(), 1.49f / 1.361f);
  EXPECT_FLOAT_EQ(s.materials[4].relativeIOR(), 1.7f / 1.1f);
}

TEST(ExteriorIndex, UnknownOrNonPositiveOutsideIsAnErrorAtItsLine) {
  test::TempDir dir;
  for (const char* value : {R"(<string name="extEta" value="syrup"/>)", R"(<float name="extEta" value="0"/>)"}) {
    const std::string file = dir.write("bad.xml", std::string("<scene version=\"0.6.0\"><shape type=\"cube\">\n"
                                                              "<bsdf type=\"conductor\">\n") +
                                                      value + "</bsdf></shape></scene>");
    try {
      loadScene(file);
      ADD_FAILURE() << "no error for " << value;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(file + ":3: error:"), std::string::npos) << e.what();
    }
  }
}

// tests/data/exterior-index.xml: metals with eta = the water's index and k = 0 reflect
// nothing, so they are black where they cover the image and the white sky shows elsewhere.
TEST(ExteriorIndex, MetalsIndexMatchedToTheirOutsideRenderBlack) {
  const Scene s = loadScene(test::sourceDir() + "/tests/data/exterior-index.xml");
  EXPECT_TRUE(s.warnings.messages.empty()) << s.warnings.messages.front();
  RenderSettings settings;
  settings.integrator = "path";
  settings.spp = 16;
  settings.seed = 5;
  RenderStats stats;
  const RgbImage img = render(s, settings, stats);
  const Color left = img.pixels[size_t(8 * img.width + 9)], right = img.pixels[size_t(8 * img.width + 22)];
  const Color corner = img.pixels[0];
  EXPECT_LT(left.y, 1e-4f);
  EXPECT_LT(right.y, 1e-4f);
  EXPECT_NEAR(corner.y, 1.0f, 1e-4f);
}

}  // namespace
}  // namespace erpt
