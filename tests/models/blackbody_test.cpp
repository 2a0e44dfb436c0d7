// <blackbody>: Planck's law in W / (m^2 sr nm) through the CIE 1931 observer to linear sRGB,
// as Mitsuba 0.6's RGB build loads it. Checked against an integration of our own here (the
// analytic CIE fit of Wyman, Sloan and Shirley 2013 and a midpoint rule instead of the CIE
// table and Gauss-Legendre), against the published chromaticity of CIE illuminant A, and in a
// render.
#include <gtest/gtest.h>

#include "models/blackbody.h"
#include "erpt/render.h"
#include "erpt/scene_loader.h"
#include "support/image_stats.h"
#include "support/test_support.h"

namespace erpt {
namespace {

// Planck's law from the radiation constants (CODATA 2018) instead of h, c and k.
double planck(double nm, double kelvin) {
  const double c1L = 1.191042972e-16, c2 = 1.438776877e-2;  // 2 h c^2 (W m^2 / sr), h c / k (m K)
  const double m = nm * 1e-9;
  return c1L / std::pow(m, 5) / (std::exp(c2 / (m * kelvin)) - 1) * 1e-9;
}

double lobe(double x, double mu, double below, double above) {
  const double t = (x - mu) / (x < mu ? below : above);
  return std::exp(-0.5 * t * t);
}

// Linear sRGB of a black body: the multi-lobe Gaussian fit of the CIE 1931 functions (within
// about 1% of the table), a midpoint rule at 0.5 nm over 360-830 nm, Y normalised by the
// fit's own y-bar integral.
Color independentBlackbody(double kelvin) {
  double X = 0, Y = 0, Z = 0, yBar = 0;
  for (double nm = 360.25; nm < 830; nm += 0.5) {
    const double xb = 1.056 * lobe(nm, 599.8, 37.9, 31.0) + 0.362 * lobe(nm, 442.0, 16.0, 26.7) -
                      0.065 * lobe(nm, 501.1, 20.4, 26.2);
    const double yb = 0.821 * lobe(nm, 568.8, 46.9, 40.5) + 0.286 * lobe(nm, 530.9, 16.3, 31.1);
    const double zb = 1.217 * lobe(nm, 437.0, 11.8, 36.0) + 0.681 * lobe(nm, 459.0, 26.0, 13.8);
    const double b = planck(nm, kelvin);
    X += b * xb;
    Y += b * yb;
    Z += b * zb;
    yBar += yb;
  }
  X /= yBar;
  Y /= yBar;
  Z /= yBar;
  return {float(3.2404542 * X - 1.5371385 * Y - 0.4985314 * Z), float(-0.9692660 * X + 1.8760108 * Y + 0.0415560 * Z),
          float(0.0556434 * X - 0.2040259 * Y + 1.0572252 * Z)};
}

// CIE 1931 chromaticity (x, y) of a linear sRGB colour.
std::pair<double, double> chromaticity(Color c) {
  const double X = 0.4124564 * c.x + 0.3575761 * c.y + 0.1804375 * c.z;
  const double Y = 0.2126729 * c.x + 0.7151522 * c.y + 0.0721750 * c.z;
  const double Z = 0.0193339 * c.x + 0.1191920 * c.y + 0.9503041 * c.z;
  return {X / (X + Y + Z), Y / (X + Y + Z)};
}

TEST(Blackbody, PlanckRadianceInWattsPerSquareMetreSteradianNanometre) {
  // 2 h c^2 / lambda^5 / (exp(h c / (lambda k T)) - 1) at 500 nm, 5000 K, worked by hand:
  // 1.19104e-16 / 3.125e-32 / (e^5.75511 - 1) = 3.81134e15 / 314.80 W / m^3 / sr, 1e-9 of it
  // per nanometre.
  EXPECT_NEAR(planckRadiance(500, 5000), 12107.2, 12107.2 * 1e-4);
  EXPECT_NEAR(planckRadiance(500, 5000), planck(500, 5000), planck(500, 5000) * 1e-6);
}

// The fit's ~1% error in the matching functions moves the colour by up to ~1% of its largest
// channel at these temperatures (more towards 1500 K, where red dominates).
TEST(Blackbody, MatchesAnIndependentIntegrationWithin1Point2Percent) {
  for (double kelvin : {2700.0, 3500.0, 5000.0, 6504.0, 10000.0}) {
    const Color ours = blackbodyLinearRgb(kelvin), theirs = independentBlackbody(kelvin);
    const float scale = std::max({theirs.x, theirs.y, theirs.z});
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(ours[c], theirs[c], 0.012f * scale) << kelvin << " K, channel " << c;
  }
  // The units as Mitsuba's: a 3500 K lamp is about (2173, 1239, 564) before its `scale`.
  const Color lamp = blackbodyLinearRgb(3500);
  EXPECT_NEAR(lamp.x, 2173, 15);
  EXPECT_NEAR(lamp.y, 1239, 10);
  EXPECT_NEAR(lamp.z, 564, 5);
}

TEST(Blackbody, KnownTemperaturesHaveTheirChromaticities) {
  // CIE illuminant A is Planck's law at 2848 K with the old c2 = 1.435e-2 m K, i.e. at
  // 2848 * 1.438777 / 1.435 = 2855.5 K today; its chromaticity is (0.44757, 0.40745).
  const auto [ax, ay] = chromaticity(blackbodyLinearRgb(2855.5));
  EXPECT_NEAR(ax, 0.44757, 3e-4);
  EXPECT_NEAR(ay, 0.40745, 3e-4);
  // 6504 K (D65's correlated colour temperature) is nearly white in sRGB, a little magenta
  // (the Planckian locus passes just below D65): (0.3135, 0.3236).
  const Color white = blackbodyLinearRgb(6504);
  const float mean = (white.x + white.y + white.z) / 3;
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(white[c] / mean, 1.0f, 0.05f) << c;
  const auto [wx, wy] = chromaticity(white);
  EXPECT_NEAR(wx, 0.3135, 5e-4);
  EXPECT_NEAR(wy, 0.3236, 5e-4);
  // Hotter is bluer, cooler redder.
  EXPECT_GT(blackbodyLinearRgb(10000).z, blackbodyLinearRgb(10000).x);
  EXPECT_GT(blackbodyLinearRgb(2000).x, 3 * blackbodyLinearRgb(2000).z);
}

TEST(Blackbody, LoaderReadsTemperatureAndScale) {
  test::TempDir dir;
  const Scene s = loadScene(dir.write("s.xml", R"(<scene version="0.6.0">
    <shape type="rectangle"><emitter type="area"><blackbody name="radiance" temperature="3500K" scale="0.01"/></emitter></shape>
    <shape type="rectangle"><emitter type="area"><blackbody name="radiance" temperature=" 6504 "/></emitter></shape>
  </scene>)"));
  EXPECT_TRUE(s.warnings.messages.empty()) << s.warnings.messages.front();
  ASSERT_EQ(s.emitters.size(), 2u);
  const Color lamp = blackbodyLinearRgb(3500) * 0.01f, white = blackbodyLinearRgb(6504);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(s.emitters[0].radiance[c], lamp[c], 1e-6f * lamp[c]) << c;
    EXPECT_NEAR(s.emitters[1].radiance[c], white[c], 1e-6f * white[c]) << c;
  }
  for (const char* bad : {R"(temperature="hot")", R"(temperature="-5")", R"(temperature="3000" scale="x")", ""}) {
    const std::string file = dir.write("bad.xml", std::string("<scene version=\"0.6.0\"><shape type=\"rectangle\">\n"
                                                              "<emitter type=\"area\">\n<blackbody name=\"radiance\" ") +
                                                      bad + "/></emitter></shape></scene>");
    try {
      loadScene(file);
      ADD_FAILURE() << "no error for " << bad;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(file + ":3: error:"), std::string::npos) << e.what();
    }
  }
}

// tests/data/blackbody-lamp.xml: a grey room lit by a 3500 K lamp only; the image's colour
// is the lamp's, whose ratios the independent integration gives.
TEST(Blackbody, LampLitRoomHasTheLampsColour) {
  const Scene s = loadScene(test::sourceDir() + "/tests/data/blackbody-lamp.xml");
  EXPECT_TRUE(s.warnings.messages.empty()) << s.warnings.messages.front();
  RenderSettings settings;
  settings.integrator = "path";
  settings.spp = 32;
  settings.seed = 11;
  RenderStats stats;
  const Color mean = test::meanOf(render(s, settings, stats));
  const Color lamp = independentBlackbody(3500);
  EXPECT_GT(mean.y, 0.05f);
  EXPECT_NEAR(mean.x / mean.y, lamp.x / lamp.y, 0.03f * lamp.x / lamp.y);
  EXPECT_NEAR(mean.z / mean.y, lamp.z / lamp.y, 0.03f * lamp.z / lamp.y);
}

}  // namespace
}  // namespace erpt
