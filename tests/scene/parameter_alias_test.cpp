// Parameters a plugin takes under two names (Mitsuba 0.6's aliases, declared once in
// src/scene/xml_properties.cpp): `diffuseReflectance` is the reflectance of `diffuse` and
// `roughdiffuse`, by value, nested texture or <ref>, in both dialects, without a warning. A
// parameter given under both names is refused at its line.
#include <gtest/gtest.h>

#include <string>

#include "erpt/scene_loader.h"
#include "support/test_support.h"

namespace erpt {
namespace {

using test::TempDir;

// The material of the scene's shape `i` (each shape is a cube).
const Material& materialOf(const Scene& s, size_t i) {
  return s.materials[size_t(s.mesh.material[s.shapes[i].firstTriangle])];
}

bool anyWarningMentions(const Scene& s, const std::string& text) {
  for (const std::string& m : s.warnings.messages)
    if (m.find(text) != std::string::npos) return true;
  return false;
}

TEST(ParameterAlias, DiffuseReflectanceIsTheReflectanceOfDiffuse) {
  TempDir dir;
  const Scene s = loadScene(dir.write("s.xml", R"(<scene version="0.6.0">
    <texture type="checkerboard" id="checks"><rgb name="color0" value="0.9"/><rgb name="color1" value="0.1"/></texture>
    <shape type="cube"><bsdf type="diffuse"><rgb name="diffuseReflectance" value="0.2, 0.4, 0.6"/></bsdf></shape>
    <shape type="cube"><bsdf type="diffuse">
      <texture type="checkerboard" name="diffuseReflectance"><rgb name="color0" value="0.7"/></texture></bsdf></shape>
    <shape type="cube"><bsdf type="diffuse"><ref name="diffuseReflectance" id="checks"/></bsdf></shape>
    <shape type="cube"><bsdf type="twosided">
      <bsdf type="diffuse"><srgb name="diffuseReflectance" value="#ffffff"/></bsdf></bsdf></shape>
  </scene>)"));
  EXPECT_TRUE(s.warnings.messages.empty()) << s.warnings.messages.front();
  const Material& plain = materialOf(s, 0);
  EXPECT_EQ(plain.kind, BsdfKind::Diffuse);
  EXPECT_EQ(plain.reflectance.texture, -1);
  EXPECT_FLOAT_EQ(plain.reflectance.value.x, 0.2f);
  EXPECT_FLOAT_EQ(plain.reflectance.value.y, 0.4f);
  EXPECT_FLOAT_EQ(plain.reflectance.value.z, 0.6f);
  const Material& nested = materialOf(s, 1);
  ASSERT_GE(nested.reflectance.texture, 0);
  EXPECT_FLOAT_EQ(s.textures[size_t(nested.reflectance.texture)].color0.y, 0.7f);
  const Material& referenced = materialOf(s, 2);
  ASSERT_GE(referenced.reflectance.texture, 0);
  EXPECT_FLOAT_EQ(s.textures[size_t(referenced.reflectance.texture)].color0.y, 0.9f);
  const Material& wrapped = materialOf(s, 3);
  EXPECT_TRUE(wrapped.twoSided);
  EXPECT_FLOAT_EQ(wrapped.reflectance.value.y, 1.0f);
}

// The names are normalized before the aliases apply: Mitsuba 3's spelling works too.
TEST(ParameterAlias, DiffuseReflectanceInTheMitsuba3Dialect) {
  TempDir dir;
  const Scene s = loadScene(dir.write("s.xml", R"(<scene version="3.0.0">
    <shape type="cube"><bsdf type="diffuse"><rgb name="diffuse_reflectance" value="0.3"/></bsdf></shape>
  </scene>)"));
  EXPECT_TRUE(s.warnings.messages.empty()) << s.warnings.messages.front();
  EXPECT_FLOAT_EQ(materialOf(s, 0).reflectance.value.x, 0.3f);
}

// roughdiffuse is rendered as diffuse (one warning, about its roughness); its reflectance,
// under either name, is kept.
TEST(ParameterAlias, RoughDiffuseTakesDiffuseReflectance) {
  TempDir dir;
  const Scene s = loadScene(dir.write("s.xml", R"(<scene version="0.6.0">
    <shape type="cube"><bsdf type="roughdiffuse"><rgb name="diffuseReflectance" value="0.25, 0.5, 0.75"/>
      <float name="alpha" value="0.3"/></bsdf></shape>
    <shape type="cube"><bsdf type="roughdiffuse"><rgb name="reflectance" value="0.1"/></bsdf></shape>
  </scene>)"));
  const Material& aliased = materialOf(s, 0);
  EXPECT_EQ(aliased.kind, BsdfKind::Diffuse);
  EXPECT_FLOAT_EQ(aliased.reflectance.value.x, 0.25f);
  EXPECT_FLOAT_EQ(aliased.reflectance.value.z, 0.75f);
  EXPECT_FLOAT_EQ(materialOf(s, 1).reflectance.value.y, 0.1f);
  ASSERT_EQ(s.warnings.messages.size(), 2u);  // one per roughdiffuse
  for (const std::string& m : s.warnings.messages)
    EXPECT_NE(m.find("roughdiffuse (Oren-Nayar)"), std::string::npos) << m;
  EXPECT_FALSE(anyWarningMentions(s, "reflectance'")) << s.warnings.messages.front();
}

// An alias belongs to its plugin: plastic's diffuse part is `diffuseReflectance` only, so a
// `reflectance` there is warned about (and the default kept), as before.
TEST(ParameterAlias, OtherPluginsDoNotTakeTheAlias) {
  TempDir dir;
  const Scene s = loadScene(dir.write("s.xml", R"(<scene version="0.6.0">
    <shape type="cube"><bsdf type="plastic"><rgb name="reflectance" value="0.9"/></bsdf></shape>
  </scene>)"));
  EXPECT_FLOAT_EQ(materialOf(s, 0).reflectance.value.x, 0.5f);
  EXPECT_TRUE(anyWarningMentions(s, "parameter 'reflectance' of <bsdf type=\"plastic\"> is not supported"))
      << (s.warnings.messages.empty() ? "no warning" : s.warnings.messages.front());
}

// One parameter under both names: a one-line error at the alias, naming the other's line.
TEST(ParameterAlias, BothNamesAreRefused) {
  TempDir dir;
  struct Case {
    std::string version, type, alias;
  };
  for (const Case& c : {Case{"0.6.0", "diffuse", "diffuseReflectance"},
                        Case{"0.6.0", "roughdiffuse", "diffuseReflectance"},
                        Case{"3.0.0", "diffuse", "diffuse_reflectance"}}) {
    const std::string file = dir.write("both.xml", "<scene version=\"" + c.version + "\">\n<shape type=\"cube\">\n" +
                                                       "<bsdf type=\"" + c.type + "\">\n" +    // line 3
                                                       "<rgb name=\"" + c.alias + "\" value=\"0.2\"/>\n" +  // line 4
                                                       "<rgb name=\"reflectance\" value=\"0.8\"/>\n" +      // line 5
                                                       "</bsdf></shape></scene>\n");
    try {
      loadScene(file);
      ADD_FAILURE() << c.type << " took both names";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
      EXPECT_EQ(what.rfind(file + ":4: error: ", 0), 0u) << what;
      EXPECT_NE(what.find("'diffuse_reflectance' and 'reflectance' (line 5)"), std::string::npos) << what;
      EXPECT_NE(what.find("<bsdf type=\"" + c.type + "\">"), std::string::npos) << what;
      EXPECT_NE(what.find("give only one"), std::string::npos) << what;
    }
  }
}

}  // namespace
}  // namespace erpt
