// Mitsuba 0.6's mixturebsdf, loaded as a chain of blends: sum_i w_i f_i evaluates (and its pdf
// and samples follow) as the mixed BSDF, with weights above 1 normalized and the rest below 1
// absorbed; nested blends on either side, textures and twosided reach every part; bad weight
// lists are one-line errors at the weights.
#include <gtest/gtest.h>

#include <cmath>
#include <regex>
#include <string>
#include <vector>

#include "erpt/scene_loader.h"
#include "models/bsdf.h"
#include "support/chi_square.h"
#include "support/test_support.h"

namespace erpt {
namespace {

using test::TempDir;
using test::testUniform;

const Material& materialNamed(const Scene& s, const std::string& name) {
  for (const Material& m : s.materials)
    if (m.name == name) return m;
  ADD_FAILURE() << "no material '" << name << "'";
  return s.materials.front();
}

SurfaceColors constantColors(const Material& m) {
  return resolveSurfaceColors(m, [](const ColorParam& p) { return p.value; });
}

Material diffuseOf(Color reflectance, bool twoSided = false) {
  Material m;
  m.kind = BsdfKind::Diffuse;
  m.reflectance.value = reflectance;
  m.twoSided = twoSided;
  return m;
}

// A random unit direction (either hemisphere).
Vec3 randomDirection(uint64_t index, uint32_t dim) {
  const float z = 1 - 2 * testUniform(index, dim), phi = 2 * kPi * testUniform(index, dim + 1);
  const float r = std::sqrt(std::max(0.0f, 1 - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// eval and pdf of (m, c) agree with those of the plain material `ref` on random direction
// pairs (both sides of the surface).
void expectSameBsdf(const Material& m, const SurfaceColors& c, const Material& ref, const char* what) {
  const SurfaceColors rc = constantColors(ref);
  for (uint64_t i = 0; i < 400; ++i) {
    const Vec3 wi = randomDirection(i, 0), wo = randomDirection(i, 2);
    const Color f = bsdfEval(m, c, wi, wo), g = bsdfEval(ref, rc, wi, wo);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(f[k], g[k], 1e-6f + 1e-5f * std::abs(g[k])) << what << " pair " << i;
    const float p = bsdfPdf(m, c, wi, wo), q = bsdfPdf(ref, rc, wi, wo);
    EXPECT_NEAR(p, q, 1e-6f + 1e-5f * q) << what << " pair " << i;
  }
}

const Color kR1(0.2f, 0.5f, 0.9f), kR2(0.8f, 0.4f, 0.1f), kR3(0.6f, 0.6f, 0.3f);

std::string rgb(Color c) {
  return "<rgb name=\"reflectance\" value=\"" + std::to_string(c.x) + ", " + std::to_string(c.y) + ", " +
         std::to_string(c.z) + "\"/>";
}
std::string diffuseXml(Color c) { return "<bsdf type=\"diffuse\">" + rgb(c) + "</bsdf>"; }

// A 0.6 scene that declares `bsdfs` (materials by id), and a cube to be a scene.
std::string scene06(const std::string& bsdfs) {
  return "<scene version=\"0.6.0\">\n" + bsdfs + "\n<shape type=\"cube\"/>\n</scene>\n";
}

TEST(MixtureBsdf, TwoDiffuseEvaluateAsTheMixedDiffuse) {
  TempDir dir;
  const Scene s = loadScene(dir.write("s.xml", scene06(R"(<bsdf type="mixturebsdf" id="mix">
      <string name="weights" value="0.3, 0.7"/>)" + diffuseXml(kR1) + diffuseXml(kR2) + "</bsdf>")));
  EXPECT_TRUE(s.warnings.messages.empty()) << s.warnings.messages.front();
  const Material& m = materialNamed(s, "mix");
  ASSERT_EQ(m.kind, BsdfKind::Blend);
  EXPECT_EQ(m.blendLeaves(), 2);  // no absorbed share
  EXPECT_NEAR(m.blendWeight.value.x, 0.7f, 1e-6f);
  expectSameBsdf(m, constantColors(m), diffuseOf(kR1 * 0.3f + kR2 * 0.7f), "0.3, 0.7");
}

// Three parts (Mitsuba's separators: spaces, commas, semicolons), the last one textured: the
// nested part's colours are resolved at the hit.
TEST(MixtureBsdf, ThreePartsWithATexturedOne) {
  TempDir dir;
  const Scene s = loadScene(dir.write("s.xml", scene06(R"(<bsdf type="mixturebsdf" id="mix">
      <string name="weights" value="0.2;0.3 0.5"/>)" + diffuseXml(kR1) + diffuseXml(kR2) +
                                                          R"(<bsdf type="diffuse"><texture type="checkerboard" name="reflectance">
        <rgb name="color0" value="0.9, 0.1, 0.4"/><rgb name="color1" value="0.05, 0.7, 0.3"/></texture></bsdf>
      </bsdf>)")));
  EXPECT_TRUE(s.warnings.messages.empty()) << s.warnings.messages.front();
  const Material& m = materialNamed(s, "mix");
  EXPECT_EQ(m.blendLeaves(), 3);
  const int mi = int(&m - s.materials.data());
  const Texture& checks = s.textures.back();
  for (const auto& [u, v] : {std::pair{0.25f, 0.25f}, std::pair{0.75f, 0.25f}}) {
    const Color r3 = checks.eval(u, v);
    expectSameBsdf(m, s.surfaceColors(mi, u, v), diffuseOf(kR1 * 0.2f + kR2 * 0.3f + r3 * 0.5f), "textured third part");
  }
  EXPECT_NE(checks.eval(0.25f, 0.25f).x, checks.eval(0.75f, 0.25f).x);  // both colours were seen
}

// Weights summing below 1: the rest is absorbed (a black part), as Mitsuba's weighted sum.
TEST(MixtureBsdf, WeightsBelowOneAbsorbTheRest) {
  TempDir dir;
  const Scene s = loadScene(dir.write("s.xml", scene06(R"(<bsdf type="mixturebsdf" id="mix">
      <string name="weights" value="0.2, 0.4"/>)" + diffuseXml(kR1) + diffuseXml(kR2) + "</bsdf>")));
  EXPECT_TRUE(s.warnings.messages.empty()) << s.warnings.messages.front();
  const Material& m = materialNamed(s, "mix");
  ASSERT_EQ(m.blendLeaves(), 3);
  const Material& black = m.blendParts[1].blendParts[1];
  EXPECT_EQ(black.kind, BsdfKind::Diffuse);
  EXPECT_EQ(black.reflectance.value.x + black.reflectance.value.y + black.reflectance.value.z, 0.0f);
  expectSameBsdf(m, constantColors(m), diffuseOf(kR1 * 0.2f + kR2 * 0.4f), "0.2, 0.4");
}

// Weights summing above 1 are normalized (ensureEnergyConservation, Mitsuba's default);
// without it Mitsuba would add energy, which a blend cannot: normalized too, with a warning.
TEST(MixtureBsdf, WeightsAboveOneAreNormalized) {
  TempDir dir;
  const std::string parts = diffuseXml(kR1) + diffuseXml(kR2) + "</bsdf>";
  const Scene s = loadScene(dir.write("s.xml", scene06(R"(<bsdf type="mixturebsdf" id="mix">
      <string name="weights" value="0.6, 0.9"/>)" + parts)));
  EXPECT_TRUE(s.warnings.messages.empty()) << s.warnings.messages.front();
  const Material& m = materialNamed(s, "mix");
  EXPECT_EQ(m.blendLeaves(), 2);
  const Material mixed = diffuseOf(kR1 * 0.4f + kR2 * 0.6f);
  expectSameBsdf(m, constantColors(m), mixed, "0.6, 0.9");

  const Scene t = loadScene(dir.write("t.xml", scene06(R"(<bsdf type="mixturebsdf" id="mix">
      <boolean name="ensureEnergyConservation" value="false"/>
      <string name="weights" value="0.6, 0.9"/>)" + parts)));
  ASSERT_EQ(t.warnings.messages.size(), 1u);
  EXPECT_NE(t.warnings.messages[0].find("t.xml:3: warning: mixturebsdf weights summing to 1.5"), std::string::npos)
      << t.warnings.messages[0];
  const Material& n = materialNamed(t, "mix");
  expectSameBsdf(n, constantColors(n), mixed, "0.6, 0.9 without ensureEnergyConservation");
}

// Nested blends on either side of a blend (a mixture whose first part is a blendbsdf, a
// blendbsdf around a mixture) keep every part's colours and weights.
TEST(MixtureBsdf, NestedBlendsOnEitherSide) {
  TempDir dir;
  const Scene s = loadScene(dir.write("s.xml", scene06(R"(
    <bsdf type="mixturebsdf" id="left"><string name="weights" value="0.5, 0.25"/>
      <bsdf type="blendbsdf"><float name="weight" value="0.25"/>)" + diffuseXml(kR1) + diffuseXml(kR2) + R"(</bsdf>
      )" + diffuseXml(kR3) + R"(</bsdf>
    <bsdf type="blendbsdf" id="right"><float name="weight" value="0.6"/>)" + diffuseXml(kR3) + R"(
      <bsdf type="mixturebsdf"><string name="weights" value="1, 3"/>)" + diffuseXml(kR1) + diffuseXml(kR2) + R"(</bsdf>
    </bsdf>)")));
  EXPECT_TRUE(s.warnings.messages.empty()) << s.warnings.messages.front();
  const Material& left = materialNamed(s, "left");
  EXPECT_EQ(left.blendLeaves(), 4);  // blend(blend(R1, R2), blend(R3, black))
  expectSameBsdf(left, constantColors(left), diffuseOf((kR1 * 0.75f + kR2 * 0.25f) * 0.5f + kR3 * 0.25f), "left");
  const Material& right = materialNamed(s, "right");
  EXPECT_EQ(right.blendLeaves(), 3);
  expectSameBsdf(right, constantColors(right), diffuseOf(kR3 * 0.4f + (kR1 * 0.25f + kR2 * 0.75f) * 0.6f), "right");
}

// twosided around a mixture makes every part two-sided, the absorbed share's too.
TEST(MixtureBsdf, TwoSidedReachesEveryPart) {
  TempDir dir;
  const Scene s = loadScene(dir.write("s.xml", scene06(R"(<bsdf type="twosided" id="both"><bsdf type="mixturebsdf">
      <string name="weights" value="0.3, 0.3, 0.2"/>)" + diffuseXml(kR1) + diffuseXml(kR2) +
                                                          diffuseXml(kR3) + "</bsdf></bsdf>")));
  const Material& m = materialNamed(s, "both");
  ASSERT_EQ(m.blendLeaves(), 4);
  std::vector<const Material*> open = {&m};
  int leaves = 0;
  while (!open.empty()) {
    const Material* p = open.back();
    open.pop_back();
    if (p->kind == BsdfKind::Blend) {
      for (const Material& q : p->blendParts) open.push_back(&q);
    } else {
      EXPECT_TRUE(p->twoSided);
      ++leaves;
    }
  }
  EXPECT_EQ(leaves, 4);
  expectSameBsdf(m, constantColors(m), diffuseOf(kR1 * 0.3f + kR2 * 0.3f + kR3 * 0.2f, true), "twosided");
}

// A glass inside nested blends: the mixture refracts through it (eta, radiance scale, Dirac
// lobe direction and value carry the glass's share). A second smooth dielectric is replaced by
// the first, with a warning.
TEST(MixtureBsdf, NestedGlassRefractsThroughTheMixture) {
  TempDir dir;
  const Scene s = loadScene(dir.write("s.xml", scene06(R"(
    <bsdf type="mixturebsdf" id="mix"><string name="weights" value="0.5, 0.5"/>)" + diffuseXml(kR1) + R"(
      <bsdf type="blendbsdf"><float name="weight" value="0.5"/><bsdf type="roughconductor"/>
        <bsdf type="dielectric"><float name="intIOR" value="1.5"/><float name="extIOR" value="1"/></bsdf></bsdf>
    </bsdf>
    <bsdf type="mixturebsdf" id="two"><string name="weights" value="0.5, 0.5"/>
      <bsdf type="dielectric"><float name="intIOR" value="1.5"/><float name="extIOR" value="1"/></bsdf>
      <bsdf type="thindielectric"/></bsdf>)")));
  ASSERT_EQ(s.warnings.messages.size(), 1u);
  EXPECT_NE(s.warnings.messages[0].find("s.xml:7: warning: mixturebsdf holds more than one smooth dielectric"),
            std::string::npos)
      << s.warnings.messages[0];
  const Material& two = materialNamed(s, "two");
  EXPECT_EQ(two.blendParts[1].kind, BsdfKind::Dielectric);

  const Material& m = materialNamed(s, "mix");
  const Material& glass = m.blendParts[1].blendParts[1];
  ASSERT_EQ(glass.kind, BsdfKind::Dielectric);
  const SurfaceColors c = constantColors(m), gc = constantColors(glass);
  EXPECT_TRUE(m.hasSpecular());
  EXPECT_FALSE(m.isPureSpecular());
  for (const Vec3 wi : {Vec3(0.3f, 0.1f, 0.9f), Vec3(0.2f, -0.1f, -0.9f)}) {
    const Vec3 in = normalize(wi);
    Vec3 wo, wg;
    ASSERT_TRUE(specularDirection(glass, in, false, wg));
    ASSERT_TRUE(specularDirection(m, in, false, wo));
    EXPECT_NEAR(dot(wo, wg), 1.0f, 1e-6f);
    EXPECT_FLOAT_EQ(bsdfEta(m, in, wo), bsdfEta(glass, in, wo));
    EXPECT_NE(bsdfEta(m, in, wo), 1.0f);
    EXPECT_FLOAT_EQ(deltaRadianceScale(m, in, wo), deltaRadianceScale(glass, in, wo));
    Color v, vg;
    float p, pg;
    ASSERT_TRUE(bsdfDeltaLobe(m, c, in, wo, v, p));
    ASSERT_TRUE(bsdfDeltaLobe(glass, gc, in, wo, vg, pg));
    EXPECT_NEAR(p, 0.25f * pg, 1e-6f);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(v[k], 0.25f * vg[k], 1e-6f);
  }
}

// Sampling a mixture of diffuse and a mirror (and an absorbed rest): the mean sample weight
// is the albedo, the integral of eval over the smooth part plus the Dirac lobe's value; every
// smooth sample's pdf is bsdfPdf's.
TEST(MixtureBsdf, SampledWeightAveragesToTheAlbedo) {
  TempDir dir;
  const Scene s = loadScene(dir.write("s.xml", scene06(R"(<bsdf type="mixturebsdf" id="mix">
      <string name="weights" value="0.3, 0.5"/>)" + diffuseXml(Color(0.8f, 0.6f, 0.4f)) + R"(
      <bsdf type="conductor"><string name="material" value="Au"/></bsdf></bsdf>)")));
  const Material& m = materialNamed(s, "mix");
  ASSERT_EQ(m.blendLeaves(), 3);
  const SurfaceColors c = constantColors(m);
  const Vec3 wi = normalize(Vec3(0.6f, 0.2f, 0.75f));

  // The smooth part's integral (midpoint rule in (cos theta, phi); the diffuse lobe's is
  // 0.3 x reflectance), and the Dirac lobe's value along the mirror direction.
  Color smooth(0.0f);
  const int n = 256;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      const float z = (a + 0.5f) / n, phi = 2 * kPi * (b + 0.5f) / n, r = std::sqrt(1 - z * z);
      smooth += bsdfEval(m, c, wi, Vec3(r * std::cos(phi), r * std::sin(phi), z)) * (2 * kPi / (float(n) * n));
    }
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(smooth[k], 0.3f * Color(0.8f, 0.6f, 0.4f)[k], 1e-4f);
  Color dirac;
  float diracProbability;
  ASSERT_TRUE(bsdfDeltaLobe(m, c, wi, Vec3(-wi.x, -wi.y, wi.z), dirac, diracProbability));
  EXPECT_NEAR(diracProbability, 0.5f, 1e-6f);
  const Color albedo = smooth + dirac;

  const uint64_t samples = 200000;
  double sum[3] = {0, 0, 0}, sumSquares[3] = {0, 0, 0};
  for (uint64_t i = 0; i < samples; ++i) {
    BsdfSample bs;
    if (!bsdfSample(m, c, wi, testUniform(i, 0), testUniform(i, 1), testUniform(i, 2), bs)) continue;
    if (!bs.delta) {
      ASSERT_NEAR(bs.pdf, bsdfPdf(m, c, wi, bs.wo), 1e-4f * bs.pdf);
    }
    for (int k = 0; k < 3; ++k) {
      sum[k] += bs.weight[k];
      sumSquares[k] += double(bs.weight[k]) * bs.weight[k];
    }
  }
  for (int k = 0; k < 3; ++k) {
    const double mean = sum[k] / samples, variance = sumSquares[k] / samples - mean * mean;
    const double sigma = std::sqrt(variance / samples);
    EXPECT_NEAR(mean, albedo[k], 5 * sigma + 1e-4) << "channel " << k << " (sigma " << sigma << ")";
  }
}

// Refused: one line, "file:line: error: cause", at the weights (or the mixture).
struct Refusal {
  const char* name;
  std::string body;  // the mixture's contents, from line 3
  int line;
  const char* cause;
};

TEST(MixtureBsdf, BadMixturesAreOneLineErrors) {
  const std::string d = "\n    <bsdf type=\"diffuse\"/>", w = "\n    <string name=\"weights\" value=\"";
  const std::vector<Refusal> refusals = {
      {"count", w + "0.5\"/>" + d + d, 3, "mixturebsdf has 1 weights for 2 nested BSDFs"},
      {"negative", w + "0.5, -0.1\"/>" + d + d, 3, "weight '-0.1' must be finite and not negative"},
      {"nan", w + "nan, 0.5\"/>" + d + d, 3, "weight 'nan' must be finite"},
      {"infinite", w + "0.5 inf\"/>" + d + d, 3, "weight 'inf' must be finite"},
      {"not a number", w + "0.5, 0.4x\"/>" + d + d, 3, "weight '0.4x' is not a number"},
      {"all zero", w + "0, 0\"/>" + d + d, 3, "must not all be 0"},
      {"empty", w + "\"/>", 2, "mixturebsdf needs nested BSDFs"},
      {"no weights", d + d, 2, "mixturebsdf needs 'weights'"},
      {"empty weights", w + " , \"/>" + d, 3, "has 0 weights for 1 nested BSDFs"},
      {"too many", w + "0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1\"/>" + d + d + d + d + d + d + d + d, 2,
       "holds 9 BSDFs"},
  };
  TempDir dir;
  for (const Refusal& r : refusals) {
    const std::string path =
        dir.write("bad.xml", "<scene version=\"0.6.0\">\n  <bsdf type=\"mixturebsdf\" id=\"mix\">" + r.body +
                                 "\n  </bsdf>\n</scene>\n");
    try {
      loadScene(path);
      ADD_FAILURE() << r.name << ": accepted";
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_TRUE(std::regex_match(message, std::regex("[^\n\r]+:[0-9]+: error: [^\n\r]+"))) << message;
      EXPECT_EQ(message.rfind(path + ":" + std::to_string(r.line) + ": error: ", 0), 0u) << r.name << ": " << message;
      EXPECT_NE(message.find(r.cause), std::string::npos) << r.name << ": " << message;
    }
  }
}

}  // namespace
}  // namespace erpt
