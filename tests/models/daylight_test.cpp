// Mitsuba 0.6's daylight (`sky`, `sun`, `sunsky`): the sun's position from date and place and
// its luminance against astronomical facts, the Hosek-Wilkie model against an independent
// evaluation of its published formula, the drawn sky's shape and the sun disk's power, the
// loader, and a diffuse floor's radiance under the sky against a quadrature.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "erpt/environment_map.h"
#include "erpt/render.h"
#include "erpt/scene_loader.h"
#include "models/sky_model.h"
#include "models/spectrum.h"
#include "models/sun_model.h"
#include "hosek_wilkie_rgb_data.h"
#include "support/chi_square.h"
#include "support/environment_scene.h"
#include "support/image_stats.h"
#include "support/test_support.h"

namespace erpt {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180;

// The sun at the equator at noon UT on the March equinox of 2000 (20 March, 07:35 UT) stands
// within about 2 degrees of the zenith (the equation of time is -7.5 minutes, i.e. 1.9 degrees
// of hour angle); at the June solstice over the Tropic of Cancer at local solar noon, within
// 0.5 degrees; and at 6:00 local solar time on the equinox it rises due east.
TEST(SunPosition, EquinoxAndSolsticeNoonsAndAnEquinoxSunrise) {
  const SunAngles noon = sunPosition({2000, 3, 20, 12, 0, 0}, {0.0, 0.0, 0.0});
  EXPECT_LT(noon.zenith / kDeg, 2.5);
  const SunAngles solstice = sunPosition({2010, 6, 21, 12, 1, 40}, {23.44, 0.0, 0.0});
  EXPECT_LT(solstice.zenith / kDeg, 0.6);
  const SunAngles sunrise = sunPosition({2000, 3, 20, 6, 7, 30}, {0.0, 0.0, 0.0});
  EXPECT_NEAR(sunrise.zenith / kDeg, 90.0, 1.0);
  EXPECT_NEAR(sunrise.azimuth / kDeg, 90.0, 1.0);  // from north towards east
  // In the afternoon it is in the west; the time zone shifts local time.
  const SunAngles afternoon = sunPosition({2000, 3, 20, 16, 7, 30}, {0.0, 0.0, 0.0});
  EXPECT_NEAR(afternoon.azimuth / kDeg, 270.0, 2.0);
  EXPECT_NEAR(afternoon.zenith / kDeg, 60.0, 1.0);
  const SunAngles shifted = sunPosition({2000, 3, 20, 18, 7, 30}, {0.0, 0.0, 2.0});
  EXPECT_NEAR(shifted.zenith, afternoon.zenith, 1e-9);
}

TEST(SunPosition, DirectionsAndAnglesAreInverse) {
  const Vec3 east = directionOf(90 * kDeg, 90 * kDeg);
  EXPECT_NEAR(east.x, 1.0f, 1e-6f);
  const Vec3 north = directionOf(90 * kDeg, 0.0);
  EXPECT_NEAR(north.z, -1.0f, 1e-6f);  // Mitsuba 0.6's azimuth 0 lies along -z
  const SunAngles a = anglesOf(normalize(Vec3(0.3f, 0.5f, 0.4f)));
  const Vec3 back = directionOf(a.zenith, a.azimuth);
  EXPECT_NEAR(back.x, normalize(Vec3(0.3f, 0.5f, 0.4f)).x, 1e-6f);
  EXPECT_NEAR(back.z, normalize(Vec3(0.3f, 0.5f, 0.4f)).z, 1e-6f);
}

// The published model, evaluated here a second way: the quintic Bezier curve over
// (elevation / (pi/2))^(1/3) by de Casteljau's construction rather than Bernstein weights,
// turbidity and albedo interpolated bilinearly, in long double.
long double casteljau(const double* points, int stride, long double x) {
  long double p[6];
  for (int k = 0; k < 6; ++k) p[k] = points[k * stride];
  for (int level = 5; level > 0; --level)
    for (int k = 0; k < level; ++k) p[k] = (1 - x) * p[k] + x * p[k + 1];
  return p[0];
}

long double parameter(const double* dataset, int count, int index, double turbidity, double albedo, double elevation) {
  const long double x = std::cbrt((long double)elevation / (3.14159265358979323846L / 2));
  const int low = int(turbidity);
  const long double rem = turbidity - low;
  auto at = [&](int a, int t) { return casteljau(dataset + (a * 10 + t - 1) * 6 * count + index, count, x); };
  long double lowValue = (1 - albedo) * at(0, low) + albedo * at(1, low);
  long double highValue = low < 10 ? (1 - albedo) * at(0, low + 1) + albedo * at(1, low + 1) : 0.0L;
  return (1 - rem) * lowValue + rem * highValue;
}

long double referenceRadiance(int channel, double turbidity, double albedo, double elevation, long double theta,
                              long double gamma) {
  long double p[9];
  for (int i = 0; i < 9; ++i)
    p[i] = parameter(kHosekWilkieRgbCoefficients[channel], 9, i, turbidity, albedo, elevation);
  const long double scale = parameter(kHosekWilkieRgbRadiance[channel], 1, 0, turbidity, albedo, elevation);
  const long double A = p[0], B = p[1], C = p[2], D = p[3], E = p[4], F = p[5], G = p[6], I = p[7], H = p[8];
  const long double chi = (1 + std::cos(gamma) * std::cos(gamma)) / std::pow(1 + H * H - 2 * H * std::cos(gamma), 1.5L);
  return (1 + A * std::exp(B / (std::cos(theta) + 0.01L))) *
         (C + D * std::exp(E * gamma) + F * std::cos(gamma) * std::cos(gamma) + G * chi + I * std::sqrt(std::cos(theta))) *
         scale;
}

TEST(HosekWilkieSky, MatchesTheModelsFormulaEvaluatedIndependently) {
  struct Case {
    double turbidity, albedo, sunElevationDeg;
  };
  for (const Case c : {Case{1.0, 0.0, 5.0}, Case{2.7, 0.3, 20.0}, Case{5.5, 1.0, 45.0}, Case{9.2, 0.15, 70.0}, Case{10.0, 0.6, 88.0}}) {
    const double elevation = c.sunElevationDeg * kDeg;
    const HosekWilkieSky sky(c.turbidity, Color(float(c.albedo)), {90 * kDeg - elevation, 1.0});
    for (double thetaDeg : {0.0, 30.0, 60.0, 85.0, 89.5})
      for (double gammaDeg : {0.5, 5.0, 40.0, 100.0, 170.0}) {
        for (int ch = 0; ch < 3; ++ch) {
          const long double ref = referenceRadiance(ch, c.turbidity, c.albedo, elevation, thetaDeg * kDeg, gammaDeg * kDeg);
          const double ours = sky.modelRadiance(ch, thetaDeg * kDeg, gammaDeg * kDeg);
          EXPECT_NEAR(ours, double(ref), 1e-7 * std::fabs(double(ref)) + 1e-12)
              << "turbidity " << c.turbidity << " theta " << thetaDeg << " gamma " << gammaDeg << " channel " << ch;
        }
      }
  }
}

// What a clear sky looks like, for every turbidity and sun elevation the model covers:
// positive radiance everywhere above the horizon, brighter around the sun than opposite it,
// and a blue zenith when the sun is high and the air clear.
TEST(HosekWilkieSky, ClearSkiesAreBrightestAroundTheSunAndBlueOverhead) {
  for (double turbidity = 1; turbidity <= 10; turbidity += 0.5)
    for (double albedo : {0.0, 0.5, 1.0})
      for (double elevationDeg : {1.0, 10.0, 30.0, 60.0, 89.0}) {
        const SunAngles sun{(90 - elevationDeg) * kDeg, 2.0};
        const HosekWilkieSky sky(turbidity, Color(float(albedo)), sun);
        for (double theta = 0; theta < 89.9; theta += 7.3)
          for (double phi = 0; phi < 360; phi += 11)
            for (int c = 0; c < 3; ++c) {
              const float v = sky.radiance(theta * kDeg, phi * kDeg)[c];
              ASSERT_TRUE(std::isfinite(v) && v > 0) << turbidity << " " << elevationDeg << " " << theta << " " << phi;
            }
        // Near the sun (5 degrees off it, towards the zenith) against the opposite side of the
        // sky at the same height.
        const double nearTheta = sun.zenith - 5 * kDeg;
        if (elevationDeg <= 60) {
          EXPECT_GT(luminance(sky.radiance(nearTheta, sun.azimuth)), luminance(sky.radiance(nearTheta, sun.azimuth + 3.14159)))
              << turbidity << " " << elevationDeg;
        }
        // (With the sun overhead the zenith is the white solar aureole.)
        if (turbidity <= 3 && elevationDeg >= 30 && elevationDeg <= 60) {
          const Color zenith = sky.radiance(0.0, 0.0);
          EXPECT_GT(zenith.z, zenith.x) << "a clear sky's zenith is blue";
        }
      }
}

TEST(HosekWilkieSky, RejectsWhatTheModelDoesNotCover) {
  EXPECT_THROW(HosekWilkieSky(0.5, Color(0.2f), {0.3, 0.0}), std::invalid_argument);
  EXPECT_THROW(HosekWilkieSky(3, Color(1.5f), {0.3, 0.0}), std::invalid_argument);
  EXPECT_THROW(HosekWilkieSky(3, Color(0.2f), {95 * kDeg, 0.0}), std::invalid_argument);  // night
}

// The drawn sky: zero below the horizon, mirror-symmetric about the sun's vertical plane, at
// its brightest in that plane (the model brightens towards the horizon, so the brightest pixel
// can lie below the sun), several times brighter at the sun than opposite it; `stretch`
// reaches below the horizon, `scale` scales.
TEST(Sky, ImageIsDarkBelowTheHorizonAndSymmetricAboutTheSun) {
  SkySettings s;
  s.sun = {50 * kDeg, 90 * kDeg};  // in the east (+x), 40 degrees up
  s.resolution = 128;
  const RgbImage img = rasterizeSky(s);
  ASSERT_EQ(img.width, 128);
  ASSERT_EQ(img.height, 64);
  int brightX = 0, brightY = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const Color c = img.at(x, y);
      if (y >= img.height / 2) {
        ASSERT_EQ(luminance(c), 0.0f) << x << "," << y;
        continue;
      }
      if (luminance(c) > luminance(img.at(brightX, brightY))) brightX = x, brightY = y;
      // Mirrored about the sun's azimuth (90 degrees), the pixel centre at phi is the one at
      // 180 degrees - phi: column 63 - x (mod 128).
      const int mirror = (img.width / 2 - 1 - x + img.width) % img.width;
      const Color m = img.at(mirror, y);
      for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(c[ch], m[ch], 1e-4f * std::max(1.0f, c[ch])) << x << "," << y;
    }
  const SunAngles brightest = anglesOf(directionOf((brightY + 0.5) * 3.14159265 / 64, (brightX + 0.5) * 2 * 3.14159265 / 128));
  EXPECT_NEAR(brightest.azimuth / kDeg, 90.0, 3.0);
  // Row 17 is centred at zenith 49.2 degrees; columns 31/32 and 95/96 straddle azimuths 90 and 270.
  EXPECT_GT(luminance(img.at(31, 17)), 3 * luminance(img.at(95, 17)));

  SkySettings stretched = s;
  stretched.stretch = 2;
  stretched.scale = 3;
  const RgbImage low = rasterizeSky(stretched);
  EXPECT_GT(luminance(low.at(10, 40)), 0.0f);  // below the horizon, reached by the stretch
  // Zenith angle z is looked up at z / 2, so just under the zenith the stretched sky is the
  // plain one, times the scale.
  const RgbImage plain = rasterizeSky(s);
  EXPECT_NEAR(luminance(low.at(5, 0)) / luminance(plain.at(5, 0)), 3.0f, 0.3f);
}

std::string skyScene(const std::string& emitter) {
  return R"(<scene version="0.6.0">
    <sensor type="perspective"><float name="fov" value="30"/>
      <transform name="toWorld"><lookat origin="0,10,0" target="0,0,0" up="0,0,1"/></transform>
      <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="16"/>
        <rfilter type="box"/></film></sensor>
    <shape type="rectangle"><transform name="toWorld"><scale value="1000"/><rotate x="1" angle="-90"/></transform>
      <bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf></shape>
    )" + emitter + "\n  </scene>";
}

// With the sun given as a world direction, the map's brightest direction is the sun's, also
// when to_world turns the sky; the date-and-place parameters are read (the default day).
TEST(Sky, LoaderPlacesTheSunAndReadsTheParameters) {
  test::TempDir dir;
  const Vec3 sunWorld = normalize(Vec3(0.3f, 0.8f, -0.5f));
  const Scene scene = loadScene(dir.write("a.xml", skyScene(R"(<emitter type="sky">
      <vector name="sunDirection" x="0.3" y="0.8" z="-0.5"/><float name="turbidity" value="4"/>
      <integer name="resolution" value="256"/><float name="scale" value="2"/>
      <transform name="toWorld"><rotate x="1" angle="20"/></transform></emitter>)")));
  ASSERT_NE(scene.environment(), nullptr);
  ASSERT_TRUE(scene.environment()->map);
  const EnvironmentMap& map = *scene.environment()->map;
  EXPECT_EQ(map.width(), 256);
  // At the sun against the opposite azimuth at the same height (in the sky's frame, which
  // to_world turns): the sun's side is several times brighter.
  const Transform rotation = Transform::rotate(1, 0, 0, 20);
  const Vec3 local = rotation.inverse().vector(sunWorld);
  const Vec3 opposite = rotation.vector(Vec3(-local.x, local.y, -local.z));
  EXPECT_GT(luminance(map.eval(sunWorld)), 3 * luminance(map.eval(opposite)));
  // The whole map is the model for that sun, turned by to_world and scaled: against the model
  // evaluated directly, at random directions above the horizon (bilinear lookup between pixel
  // centres: a median error well under 1%).
  const HosekWilkieSky sky(4, Color(0.2f), anglesOf(normalize(local)));
  std::vector<double> errors;
  for (int i = 0; i < 4000; ++i) {
    const Vec3 d = map.uvToDirection(test::testUniform(i, 0), test::testUniform(i, 1));
    const SunAngles a = anglesOf(normalize(rotation.inverse().vector(d)));
    if (a.zenith > 85 * kDeg) continue;
    const float expected = 2 * luminance(sky.radiance(a.zenith, a.azimuth));
    errors.push_back(std::fabs(luminance(map.eval(d)) / expected - 1));
  }
  ASSERT_GT(errors.size(), 1000u);
  std::sort(errors.begin(), errors.end());
  EXPECT_LT(errors[errors.size() / 2], 0.005);
  EXPECT_LT(errors[errors.size() * 9 / 10], 0.03);
  EXPECT_TRUE(scene.warnings.messages.empty()) << scene.warnings.messages.front();

  const Scene dated = loadScene(dir.write("b.xml", skyScene(R"(<emitter type="sky">
      <integer name="year" value="2010"/><integer name="month" value="7"/><integer name="day" value="10"/>
      <float name="hour" value="15"/><float name="latitude" value="35.6894"/><float name="longitude" value="139.6917"/>
      <float name="timezone" value="9"/><spectrum name="albedo" value="0.15"/><float name="stretch" value="1.2"/>
      <boolean name="extend" value="false"/></emitter>)")));
  ASSERT_NE(dated.environment(), nullptr);
  EXPECT_TRUE(dated.warnings.messages.empty()) << dated.warnings.messages.front();
}

// A white-ish diffuse floor (albedo 0.5) seen from above reflects (0.5 / pi) times the sky's
// irradiance, computed here by quadrature of the map's own radiance over the upper hemisphere.
TEST(Sky, DiffuseFloorReflectsTheSkysIrradiance) {
  test::TempDir dir;
  const Scene scene = loadScene(dir.write("s.xml", skyScene(R"(<emitter type="sky">
      <vector name="sunDirection" x="0.5" y="0.6" z="0.2"/><float name="turbidity" value="2.5"/>
      <integer name="resolution" value="128"/></emitter>)")));
  const EnvironmentMap& map = *scene.environment()->map;
  double irradiance[3] = {0, 0, 0};
  const int nt = 512, np = 1024;
  for (int t = 0; t < nt; ++t)
    for (int p = 0; p < np; ++p) {
      const double theta = (t + 0.5) * 3.14159265358979 / 2 / nt, phi = (p + 0.5) * 2 * 3.14159265358979 / np;
      const Vec3 d = directionOf(theta, phi);
      const Color l = map.eval(d);
      const double w = std::cos(theta) * std::sin(theta) * (3.14159265358979 / 2 / nt) * (2 * 3.14159265358979 / np);
      for (int c = 0; c < 3; ++c) irradiance[c] += l[c] * w;
    }
  RenderSettings s;
  s.spp = 256;
  s.seed = 5;
  RenderStats stats;
  const Color m = test::meanOf(render(scene, s, stats));
  EXPECT_EQ(stats.invalidSamples, 0u);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(m[c], 0.5 / 3.14159265358979 * irradiance[c], 0.01 * m[c]) << "channel " << c;
}

// The sun's luminance at sea level with the sun overhead in clear air is about 1.6e9 cd/m^2
// (683 lm/W times the integral of radiance x y-bar, here Y times the integral of y-bar); lower
// suns and hazier air dim and redden it.
TEST(SunModel, NoonSunHasTheSunsLuminanceAndLowSunsAreDimmerAndRedder) {
  // Y is normalised so that a flat spectrum of 1 has Y = 1; the CIE 1931 y-bar integrates to
  // 106.857 nm.
  EXPECT_NEAR(luminance(spectrumToLinearRgb([](double) { return 1.0; })), 1.0f, 2e-3f);
  const double kYBarIntegralNm = 106.857;
  const Color noon = sunRadiance(0.0, 2.0);
  const double luminanceCdPerM2 = 683.0 * luminance(noon) * kYBarIntegralNm;
  EXPECT_GT(luminanceCdPerM2, 1.2e9);
  EXPECT_LT(luminanceCdPerM2, 1.9e9);
  const Color low = sunRadiance(80 * kDeg, 2.0), hazy = sunRadiance(0.0, 8.0);
  EXPECT_LT(luminance(low), 0.5f * luminance(noon));
  EXPECT_LT(luminance(hazy), 0.7f * luminance(noon));
  EXPECT_GT(low.x / low.z, 1.5f * noon.x / noon.z);  // redder
}

// However wide it is drawn (sun_radius_scale) and wherever it stands, the disk carries the
// power of the true sun disk: the sum of radiance x pixel solid angle.
TEST(SunModel, DrawnDiskKeepsTheSunsPower) {
  const double diskSolidAngle = 2 * 3.14159265358979 * (1 - std::cos(kSunAngularRadius));
  for (double radiusScale : {1.0, 4.0, 30.0})
    for (SunAngles sun : {SunAngles{0.02, 0.0}, SunAngles{40 * kDeg, 3.0}, SunAngles{88 * kDeg, 5.5}}) {
      RgbImage img;
      img.width = 256;
      img.height = 128;
      img.pixels.assign(256 * 128, Color(0.0f));
      addSunToImage(img, sun, Color(1.0f, 2.0f, 3.0f), radiusScale);
      double power = 0;
      const Vec3 axis = directionOf(sun.zenith, sun.azimuth);
      double farthest = 0;
      for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
          if (img.at(x, y).x == 0) continue;
          const double solidAngle = 2 * 3.14159265358979 / 256 * (std::cos(3.14159265358979 * y / 128) -
                                                                   std::cos(3.14159265358979 * (y + 1) / 128));
          power += img.at(x, y).x * solidAngle;
          const Vec3 centre = directionOf((y + 0.5) * 3.14159265358979 / 128, (x + 0.5) * 2 * 3.14159265358979 / 256);
          farthest = std::max(farthest, double(std::acos(std::min(1.0f, dot(centre, axis)))));
        }
      EXPECT_NEAR(power / diskSolidAngle, 1.0, 1e-3) << radiusScale << " " << sun.zenith;
      // Only pixels the widened disk touches (plus a pixel's diagonal, 1.6 degrees here).
      EXPECT_LT(farthest, kSunAngularRadius * radiusScale + 1.7 * kDeg);
    }
}

std::string daylightOnly(const std::string& emitters) {
  return "<scene version=\"0.6.0\">" + emitters + "</scene>";
}

// `sunsky` is `sky` plus `sun` in one map (with sky_scale and sun_scale); the two given as
// separate emitters make the same map; sun_radius_scale 0 makes the sun a directional light
// with the disk's irradiance; a daylight emitter next to an envmap is an error.
TEST(Daylight, SunskyIsSkyPlusSunAndARadiusOfZeroIsADirectionalLight) {
  test::TempDir dir;
  const std::string where = R"(<vector name="sunDirection" x="0.2" y="0.7" z="0.4"/><integer name="resolution" value="128"/>
      <float name="turbidity" value="3.5"/><transform name="toWorld"><rotate y="1" angle="30"/></transform>)";
  const Scene both = loadScene(dir.write("a.xml", daylightOnly(R"(<emitter type="sunsky"><float name="skyScale" value="2"/>
      <float name="sunScale" value="0.5"/><float name="sunRadiusScale" value="3"/>)" + where + "</emitter>")));
  const Scene two = loadScene(dir.write("b.xml", daylightOnly(R"(<emitter type="sky"><float name="scale" value="2"/>)" +
                                                                where + R"(</emitter><emitter type="sun">
      <float name="scale" value="0.5"/><float name="sunRadiusScale" value="3"/>)" + where + "</emitter>")));
  ASSERT_EQ(both.emitters.size(), 1u);
  ASSERT_EQ(two.emitters.size(), 1u);
  const EnvironmentMap &a = *both.environment()->map, &b = *two.environment()->map;
  for (int i = 0; i < 3000; ++i) {
    const Vec3 d = a.uvToDirection(test::testUniform(i, 0), test::testUniform(i, 1));
    EXPECT_NEAR(luminance(a.eval(d)), luminance(b.eval(d)), 1e-5f * std::max(1.0f, luminance(a.eval(d))));
  }
  // The sun is in the map, where sunDirection says (to_world is applied to it as to the map).
  const Vec3 sunWorld = normalize(Vec3(0.2f, 0.7f, 0.4f));
  EXPECT_GT(luminance(a.eval(sunWorld)), 100 * luminance(a.eval(normalize(Vec3(-0.2f, 0.7f, -0.4f)))));

  const Scene directional = loadScene(dir.write("c.xml", daylightOnly(R"(<emitter type="sunsky">
      <float name="sunRadiusScale" value="0"/>)" + where + "</emitter>")));
  ASSERT_EQ(directional.emitters.size(), 2u);
  const Emitter& sun = directional.emitters[0];
  ASSERT_EQ(sun.kind, EmitterKind::Directional);
  EXPECT_GT(dot(sun.axis, -sunWorld), 0.99999f);
  const float diskSolidAngle = float(2 * 3.14159265358979 * (1 - std::cos(kSunAngularRadius)));
  const SunAngles local = anglesOf(normalize(Transform::rotate(0, 1, 0, 30).inverse().vector(sunWorld)));
  EXPECT_NEAR(luminance(sun.radiance), luminance(sunRadiance(local.zenith, 3.5)) * diskSolidAngle,
              1e-4f * luminance(sun.radiance));
  ASSERT_NE(directional.environment(), nullptr);
  // No sun in the map then.
  EXPECT_LT(luminance(directional.environment()->map->eval(sunWorld)), 10.0f);

  writeImageAtomic(dir.file("e.exr"), test::skyImage());
  EXPECT_THROW(loadScene(dir.write("d.xml", daylightOnly(R"(<emitter type="envmap"><string name="filename" value="e.exr"/>
      </emitter><emitter type="sun"/>)"))),
               InputError);
}

}  // namespace
}  // namespace erpt
