// The `envmap` emitter: Mitsuba's direction convention, importance sampling against its pdf
// (chi-square) and against uniform sampling, a uniform map against `constant`, the loader.
#include <gtest/gtest.h>

#include <cmath>

#include "erpt/environment_map.h"
#include "models/light_sampler.h"
#include "erpt/render.h"
#include "erpt/scene_loader.h"
#include "models/sky_model.h"
#include "core/warp.h"
#include "support/chi_square.h"
#include "support/environment_scene.h"
#include "support/image_stats.h"
#include "support/test_support.h"

namespace erpt {
namespace {

// Every pixel a different colour.
RgbImage numberedImage(int w, int h) {
  RgbImage img;
  img.width = w;
  img.height = h;
  for (int i = 0; i < w * h; ++i) img.pixels.push_back(Color(float(i), float(i % w), float(i / w)) + Color(1.0f));
  return img;
}

void expectColorNear(Color a, Color b, float relative, const std::string& what) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], relative * std::max(1.0f, std::abs(b[c]))) << what << " channel " << c;
}

TEST(EnvironmentMap, MapsDirectionsAsMitsuba) {
  const RgbImage img = numberedImage(8, 4);
  const EnvironmentMap map(img, 2.0f, Transform{});
  float u, v;
  map.directionToUv(Vec3(0, 1, 0), u, v);
  EXPECT_NEAR(v, 0.0f, 1e-6f);  // +y: the top row
  map.directionToUv(Vec3(0, 0, 1), u, v);
  EXPECT_NEAR(u, 0.5f, 1e-6f);  // +z: the middle column
  EXPECT_NEAR(v, 0.5f, 1e-6f);
  map.directionToUv(Vec3(1, 0, 0), u, v);
  EXPECT_NEAR(u, 0.25f, 1e-6f);  // +x: a quarter in
  map.directionToUv(Vec3(-1, 0, 0), u, v);
  EXPECT_NEAR(u, 0.75f, 1e-6f);
  // At every pixel centre the (bilinear) radiance is that pixel's value times the scale.
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const Vec3 d = map.uvToDirection((x + 0.5f) / img.width, (y + 0.5f) / img.height);
      EXPECT_NEAR(length(d), 1.0f, 1e-5f);
      expectColorNear(map.eval(d), img.at(x, y) * 2.0f, 1e-4f, "pixel " + std::to_string(x) + "," + std::to_string(y));
    }
  // Half way between two pixel centres of a row: their average; across u = 0 it wraps around.
  expectColorNear(map.eval(map.uvToDirection(1.0f / 8, 1.5f / 4)), (img.at(0, 1) + img.at(1, 1)) * 1.0f, 1e-4f, "between");
  expectColorNear(map.eval(map.uvToDirection(0.0f, 1.5f / 4)), (img.at(0, 1) + img.at(7, 1)) * 1.0f, 1e-4f, "wrap");
}

TEST(EnvironmentMap, ToWorldRotatesTheMap) {
  const RgbImage img = numberedImage(16, 8);
  const EnvironmentMap plain(img, 1.0f, Transform{});
  const Transform rotation = Transform::rotate(0.3, 1, 0.2, 50);
  const EnvironmentMap rotated(img, 1.0f, rotation);
  for (int i = 0; i < 200; ++i) {
    const Vec3 local = squareToUniformSphere(test::testUniform(i, 0), test::testUniform(i, 1));
    const Vec3 world = normalize(rotation.vector(local));
    expectColorNear(rotated.eval(world), plain.eval(local), 1e-3f, "direction " + std::to_string(i));
    EXPECT_NEAR(rotated.pdf(world), plain.pdf(local), 1e-3f * plain.pdf(local));
  }
}

// Sampled directions against pdf() over the sphere, in cells of equal solid angle (this
// checks the solid-angle measure). A smooth 256x128 map, so that the cells' quadrature of the
// pixel-wise constant pdf is exact to ~1e-5 (sharp edges, like the sun's, are checked per pixel
// below).
TEST(EnvironmentMap, SampledDirectionsFollowThePdf) {
  RgbImage smooth;
  smooth.width = 256;
  smooth.height = 128;
  for (int r = 0; r < smooth.height; ++r)
    for (int c = 0; c < smooth.width; ++c) {
      const float theta = kPi * (r + 0.5f) / smooth.height, phi = 2 * kPi * (c + 0.5f) / smooth.width;
      const float value = 1.0f + 0.8f * std::sin(theta) * std::cos(phi) + 0.5f * std::cos(theta);
      smooth.pixels.push_back(Color(value, 0.5f * value, 1.5f * value));
    }
  const EnvironmentMap map(smooth, 1.0f, Transform::rotate(1, 0, 0.5, 35));
  uint64_t mismatched = 0;
  const test::ChiSquareResult r = test::chiSquareTest(
      [&](uint64_t i, Vec3& d) {
        float pdf;
        if (!map.sample(test::testUniform(i, 0), test::testUniform(i, 1), d, pdf)) return false;
        mismatched += std::abs(pdf - map.pdf(d)) > 1e-4f * pdf;
        return true;
      },
      [&](Vec3 d) { return map.pdf(d); }, 24, 48, 1000000, 16);
  EXPECT_GT(r.pValue, 1e-3) << r.summary();
  EXPECT_NEAR(r.pdfIntegral, 1.0, 0.005) << r.summary();
  EXPECT_EQ(mismatched, 0u);
}

// The one-lookup forms (evalAndPdf, sample with its radiance) return the bits of eval() and
// pdf(): the renderers use them interchangeably (an escaping ray's radiance and light pdf, a
// sampled direction's radiance). Directions from sampling and uniform ones, on a map whose
// columns wrap (the bilinear lookup at u near 0 and 1).
TEST(EnvironmentMap, OneLookupFormsEqualEvalAndPdf) {
  const EnvironmentMap map(numberedImage(7, 5), 1.5f, Transform::rotate(0.3f, 1, 0.2f, 50));
  size_t checked = 0;
  for (uint64_t i = 0; i < 20000; ++i) {
    Vec3 d;
    float pdf;
    Color radiance;
    if (map.sample(test::testUniform(i, 0), test::testUniform(i, 1), d, pdf, &radiance)) {
      ASSERT_EQ(pdf, map.pdf(d));
      for (int c = 0; c < 3; ++c) ASSERT_EQ(radiance[c], map.eval(d)[c]);
      ++checked;
    }
    const Vec3 u = squareToUniformSphere(test::testUniform(i, 2), test::testUniform(i, 3));
    float pdfU;
    const Color le = map.evalAndPdf(u, pdfU);
    ASSERT_EQ(pdfU, map.pdf(u));
    for (int c = 0; c < 3; ++c) ASSERT_EQ(le[c], map.eval(u)[c]);
  }
  EXPECT_GT(checked, 19000u);
}

// Per pixel of the map: the counts of sampled directions against the pdf integrated over the
// pixel, chi-square. The integral: pdf x sin(theta) is bilinear in uv between pixel centres,
// so the midpoint rule over the pixel's quarters (whose edges are the centre lines) is exact,
// with d omega = 2 pi^2 sin(theta) du dv.
void expectSampledPixelsFollowThePdf(const EnvironmentMap& map) {
  const int w = map.width(), h = map.height();
  const uint64_t n = 2000000;
  std::vector<double> observed(size_t(w) * h, 0), expected(size_t(w) * h, 0);
  uint64_t failed = 0;
  for (uint64_t i = 0; i < n; ++i) {
    Vec3 d;
    float pdf;
    // (false only where rounding carries a direction across a pixel edge into a black pixel,
    // as at the drawn sky's horizon: rare, and counted below)
    if (!map.sample(test::testUniform(i, 0), test::testUniform(i, 1), d, pdf)) {
      ++failed;
      continue;
    }
    float u, v;
    map.directionToUv(d, u, v);
    observed[size_t(std::min(h - 1, int(v * h))) * w + size_t(std::min(w - 1, int(u * w)))] += 1;
  }
  double total = 0;
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) {
      double integral = 0;
      for (int qv = 0; qv < 2; ++qv)
        for (int qu = 0; qu < 2; ++qu) {
          const double u = (c + 0.25 + 0.5 * qu) / w, v = (r + 0.25 + 0.5 * qv) / h;
          const Vec3 d = map.uvToDirection(float(u), float(v));
          integral += double(map.pdf(d)) * 2 * kPi * kPi * std::sin(kPi * v) * (0.25 / (double(w) * h));
        }
      expected[size_t(r) * w + c] = integral * double(n);
      total += expected[size_t(r) * w + c];
    }
  EXPECT_LE(failed, n / 100000);
  EXPECT_NEAR(total / double(n), 1.0, 1e-4);  // the pdf integrates to one
  double statistic = 0, pooledObserved = 0, pooledExpected = 0;
  int bins = 0;
  for (size_t i = 0; i < observed.size(); ++i) {
    if (expected[i] < 5) {  // pool the rare pixels into one bin
      pooledObserved += observed[i], pooledExpected += expected[i];
      continue;
    }
    statistic += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
    ++bins;
  }
  if (pooledExpected > 0) {
    statistic += (pooledObserved - pooledExpected) * (pooledObserved - pooledExpected) / pooledExpected;
    ++bins;
  }
  EXPECT_GT(test::chiSquarePValue(statistic, bins - 1), 1e-3) << "chi2 " << statistic << " over " << bins << " bins";
}

// A test image with a small bright sun, and Mitsuba 0.6's `sky` as drawn for the renderer.
TEST(EnvironmentMap, SampledPixelsFollowThePdf) {
  expectSampledPixelsFollowThePdf(EnvironmentMap(test::skyImage(), 1.0f, Transform::rotate(1, 0, 0.5, 35)));
  SkySettings sky;
  sky.sun = {60 * kPi / 180, 1.0};
  sky.resolution = 96;
  expectSampledPixelsFollowThePdf(EnvironmentMap(rasterizeSky(sky), 1.0f, Transform{}));
}

// Irradiance on a tilted plane: the map's importance sampling, uniform sphere sampling and a
// fine quadrature of the bilinear radiance agree (4 standard errors plus the quadrature's 0.5%).
TEST(EnvironmentMap, ImportanceSamplingMatchesUniformSampling) {
  const EnvironmentMap map(test::skyImage(), 1.0f, Transform::rotate(0, 1, 0, 20));
  const Vec3 n = normalize(Vec3(0.4f, 0.8f, 0.3f));
  auto irradianceTerm = [&](Vec3 d) { return luminance(map.eval(d)) * std::max(0.0f, dot(d, n)); };
  double quadrature = 0;
  const int nt = 1024, np = 2048;
  for (int t = 0; t < nt; ++t)
    for (int p = 0; p < np; ++p) {
      const float theta = (t + 0.5f) * kPi / nt, phi = (p + 0.5f) * 2 * kPi / np;
      quadrature += irradianceTerm(map.uvToDirection(phi / (2 * kPi), theta / kPi)) * std::sin(theta) * (kPi / nt) *
                    (2 * kPi / np);
    }
  auto estimate = [&](bool importance, int count, double& mean, double& error) {
    double sum = 0, sum2 = 0;
    for (int i = 0; i < count; ++i) {
      const float u1 = test::testUniform(i, 0, 77), u2 = test::testUniform(i, 1, 77);
      Vec3 d;
      float pdf;
      double x = 0;
      if (importance) {
        if (map.sample(u1, u2, d, pdf)) x = irradianceTerm(d) / pdf;
      } else {
        d = squareToUniformSphere(u1, u2);
        x = irradianceTerm(d) / kUniformSpherePdf;
      }
      sum += x, sum2 += x * x;
    }
    mean = sum / count;
    error = std::sqrt(std::max(0.0, sum2 / count - mean * mean) / count);
  };
  double importanceMean, importanceError, uniformMean, uniformError;
  estimate(true, 200000, importanceMean, importanceError);
  estimate(false, 2000000, uniformMean, uniformError);
  // The point of importance sampling (the sun): per sample, at most half the standard deviation.
  EXPECT_LT(importanceError * std::sqrt(200000.0), 0.5 * uniformError * std::sqrt(2000000.0));
  EXPECT_NEAR(importanceMean, quadrature, 4 * importanceError + 0.005 * quadrature);
  EXPECT_NEAR(uniformMean, quadrature, 4 * uniformError + 0.005 * quadrature);
}

// The light sampler hands out the map's directions with the map's pdf, and pdfEnvironment()
// says the same for any direction.
TEST(EnvironmentMap, LightSamplerUsesTheMapsDensity) {
  test::TempDir dir;
  const Scene scene = loadScene(test::writeEnvmapGlassScene(dir));
  ASSERT_NE(scene.environment(), nullptr);
  ASSERT_TRUE(scene.environment()->map);
  const LightSampler lights(scene);
  for (int i = 0; i < 2000; ++i) {
    LightSample ls;
    ASSERT_TRUE(lights.sample(Vec3(0, 0.1f, 0), test::testUniform(i, 0), test::testUniform(i, 1), test::testUniform(i, 2), ls));
    ASSERT_TRUE(ls.environment);
    EXPECT_NEAR(ls.pdf, lights.pdfEnvironment(ls.direction), 1e-4f * ls.pdf);
    EXPECT_NEAR(ls.pdf, scene.environment()->map->pdf(ls.direction), 1e-4f * ls.pdf);  // the only light
    expectColorNear(ls.radiance, scene.environment()->map->eval(ls.direction), 1e-5f, "radiance");
  }
}

// A uniform map is the constant environment: a diffuse sphere in it (fills the image) reflects
// its albedo times the radiance, as under `constant` (furnace_test.cpp), in every integrator.
TEST(EnvironmentMap, UniformMapIsTheConstantEnvironment) {
  test::TempDir dir;
  RgbImage flat;
  flat.width = 16;
  flat.height = 8;
  flat.pixels.assign(16 * 8, Color(2.0f));
  writeImageAtomic(dir.file("flat.exr"), flat);
  const Scene scene = loadScene(dir.write("s.xml", R"(<scene version="3.0.0">
    <sensor type="perspective"><float name="fov" value="10"/>
      <transform name="to_world"><lookat origin="0,0,8" target="0,0,0" up="0,1,0"/></transform>
      <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="16"/>
        <rfilter type="box"/></film></sensor>
    <shape type="sphere"><float name="radius" value="1"/>
      <bsdf type="diffuse"><rgb name="reflectance" value="0.6, 0.3, 0.9"/></bsdf></shape>
    <emitter type="envmap"><string name="filename" value="flat.exr"/></emitter>
  </scene>)"));
  for (const char* integrator : {"path", "direct", "erpt", "pmc-er"}) {
    RenderSettings s;
    s.integrator = integrator;
    s.spp = std::string(integrator) == "path" || std::string(integrator) == "direct" ? 1024 : 64;
    s.seed = 9;
    RenderStats stats;
    const Color m = test::meanOf(render(scene, s, stats));
    EXPECT_EQ(stats.invalidSamples, 0u);
    EXPECT_NEAR(m.x, 1.2f, 0.01f * 1.2f) << integrator;
    EXPECT_NEAR(m.y, 0.6f, 0.01f * 0.6f) << integrator;
    EXPECT_NEAR(m.z, 1.8f, 0.01f * 1.8f) << integrator;
  }
}

TEST(EnvironmentMap, LoaderReadsBothDialectsAndRejectsBadMaps) {
  test::TempDir dir;
  writeImageAtomic(dir.file("sky.exr"), test::skyImage());
  // Mitsuba 0.6: toWorld, scale, gamma 1 (linear: no change for an EXR).
  const Scene old = loadScene(dir.write("old.xml", R"(<scene version="0.6.0">
    <emitter type="envmap"><string name="filename" value="sky.exr"/><float name="scale" value="3"/>
      <float name="gamma" value="1"/><boolean name="cache" value="false"/>
      <transform name="toWorld"><rotate y="1" angle="90"/></transform></emitter></scene>)"));
  ASSERT_NE(old.environment(), nullptr);
  ASSERT_TRUE(old.environment()->map);
  EXPECT_TRUE(old.warnings.messages.empty()) << old.warnings.messages.front();
  const EnvironmentMap reference(test::skyImage(), 3.0f, Transform::rotate(0, 1, 0, 90));
  const Vec3 d = normalize(Vec3(0.3f, 0.5f, -0.2f));
  expectColorNear(old.environment()->map->eval(d), reference.eval(d), 1e-5f, "0.6 dialect");

  RgbImage black = test::skyImage();
  for (Color& c : black.pixels) c = Color(0.0f);
  writeImageAtomic(dir.file("black.exr"), black);
  RgbImage nan = test::skyImage();
  nan.at(3, 4) = Color(std::nanf(""), 0, 0);
  writeImageAtomic(dir.file("nan.exr"), nan);
  struct Bad {
    const char* emitter;
    const char* says;
  };
  for (const Bad& bad : {Bad{R"(<emitter type="envmap"/>)", "needs a 'filename'"},
                         Bad{R"(<emitter type="envmap"><string name="filename" value="none.exr"/></emitter>)", "not found"},
                         Bad{R"(<emitter type="envmap"><string name="filename" value="black.exr"/></emitter>)", "black"},
                         Bad{R"(<emitter type="envmap"><string name="filename" value="nan.exr"/></emitter>)", "non-finite pixel (3, 4)"},
                         Bad{R"(<emitter type="envmap"><string name="filename" value="sky.exr"/><float name="scale" value="-1"/></emitter>)",
                             "scale"},
                         Bad{R"(<emitter type="constant"/><emitter type="envmap"><string name="filename" value="sky.exr"/></emitter>)",
                             "only one environment"}}) {
    const std::string path = dir.write("bad.xml", std::string("<scene version=\"3.0.0\">\n") + bad.emitter + "</scene>");
    try {
      loadScene(path);
      ADD_FAILURE() << bad.emitter << " loaded";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(bad.says), std::string::npos) << what;
      EXPECT_NE(what.find("bad.xml:2"), std::string::npos) << what;  // file and line of the element
    }
  }
}

}  // namespace
}  // namespace erpt
