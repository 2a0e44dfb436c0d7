// Every integrator and seed sampler against answers that no renderer made: scenes whose
// image is known in closed form, block by block over independent runs
// (support/closed_form_check.h). The reference of each test is the formula named at its scene;
// nothing here compares with the path tracer.
//
// - A sphere light over a diffuse plane: L = rho Le r^2 h / d^3 on the plane (the sphere, seen
//   from a point below its horizon-free side, is a point source of intensity pi r^2 Le).
// - A rectangle light over a diffuse plane: Lambert's polygon formula for the irradiance.
// - A closed furnace: a sphere lit and seen from inside, emission Le and albedo a everywhere:
//   L = Le (1 - a^D) / (1 - a) for paths of at most D segments (Le / (1 - a) unbounded).
// - A glass sphere in a white furnace: invisible, L = the environment's radiance everywhere.
//
// The integrators: path, direct, bdpt (MIS), each BDPT strategy family alone (--bdpt-weights
// none with s = 0, s = 1 or t = 1), and ERPT, PMC-ER and MLT with path-traced and with BDPT
// seeds, and ERPT with the bidirectional mutation. Each runs on the scenes whose paths it can
// make (light tracing cannot see through glass; next-event estimation alone misses the light
// seen directly).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "erpt/bdpt_settings.h"
#include "erpt/erpt_settings.h"
#include "erpt/mlt_settings.h"
#include "erpt/pmc_settings.h"
#include "erpt/render.h"
#include "erpt/scene_loader.h"
#include "support/closed_form_check.h"
#include "support/test_support.h"

namespace erpt {
namespace {

constexpr int kWidth = 30, kHeight = 20, kBlock = 5, kRuns = 24;

// The plane scenes' camera looks down at the floor beside the light, which stays out of view.
const char* kPlaneCamera = R"(
  <sensor type="perspective"><float name="fov" value="30"/>
    <transform name="to_world"><lookat origin="1.2,0,3" target="1.2,0,0" up="0,1,0"/></transform>
    <film type="hdrfilm"><integer name="width" value="30"/><integer name="height" value="20"/>
      <rfilter type="box"/></film></sensor>
  <shape type="rectangle"><transform name="to_world"><scale value="10"/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf></shape>)";

constexpr float kAlbedo = 0.5f;
constexpr int kFurnaceDepth = 5;  // paths of up to five segments keep BDPT's seeds cheap

// Where a camera ray meets the floor z = 0 (the plane scenes' cameras always see it).
Vec3 floorPoint(Vec3 o, Vec3 d) { return o + d * (-o.z / d.z); }

enum Scenes : unsigned { kSphereLight = 1, kRectangleLight = 2, kClosedFurnace = 4, kGlassInFurnace = 8 };

struct ClosedForm {
  std::string name, xml;
  int maxDepth;  // -1: unbounded
  std::function<Color(Vec3, Vec3)> radiance;
};

ClosedForm sphereLight() {
  const Vec3 c(0.0f, -0.2f, 0.4f);
  const float r = 0.2f, le = 10;
  return {"SphereLight",
          std::string(R"(<scene version="3.0.0">)") + kPlaneCamera + R"(
  <shape type="sphere"><point name="center" value="0, -0.2, 0.4"/><float name="radius" value="0.2"/>
    <emitter type="area"><rgb name="radiance" value="10"/></emitter></shape></scene>)",
          2, [=](Vec3 o, Vec3 d) {
            const Vec3 p = floorPoint(o, d), toCentre = c - p;
            const double dist = length(toCentre);
            return Color(float(kAlbedo * le * r * r * c.z / (dist * dist * dist)));
          }};
}

// Lambert: E = Le / 2 sum_i angle(u_i, u_i+1) n . normalize(u_i x u_i+1), u_i the unit vectors
// to the polygon's corners.
ClosedForm rectangleLight() {
  const float le = 5, half = 0.25f, height = 1;
  return {"RectangleLight",
          std::string(R"(<scene version="3.0.0">)") + kPlaneCamera + R"(
  <shape type="rectangle"><transform name="to_world"><scale value="0.25"/><rotate x="1" angle="180"/>
    <translate z="1"/></transform>
    <emitter type="area"><rgb name="radiance" value="5"/></emitter></shape></scene>)",
          2, [=](Vec3 o, Vec3 d) {
            const Vec3 p = floorPoint(o, d);
            const Vec3 corners[4] = {{-half, -half, height}, {half, -half, height}, {half, half, height}, {-half, half, height}};
            double sum = 0;
            for (int i = 0; i < 4; ++i) {
              const Vec3 a = normalize(corners[i] - p), b = normalize(corners[(i + 1) % 4] - p);
              const Vec3 n = cross(a, b);
              sum += std::acos(std::clamp(double(dot(a, b)), -1.0, 1.0)) * n.z / length(n);
            }
            return Color(float(kAlbedo / kPi * le / 2 * std::abs(sum)));
          }};
}

ClosedForm closedFurnace() {
  return {"ClosedFurnace", R"(<scene version="3.0.0">
  <sensor type="perspective"><float name="fov" value="70"/>
    <transform name="to_world"><lookat origin="0.1,0.2,0" target="1,0.3,0.2" up="0,0,1"/></transform>
    <film type="hdrfilm"><integer name="width" value="30"/><integer name="height" value="20"/>
      <rfilter type="box"/></film></sensor>
  <shape type="sphere"><float name="radius" value="1"/><boolean name="flip_normals" value="true"/>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf>
    <emitter type="area"><rgb name="radiance" value="1"/></emitter></shape></scene>)",
          kFurnaceDepth, [](Vec3, Vec3) {
            // Paths of 1 .. D segments: Le (1 + a + ... + a^(D-1)).
            return Color(float((1 - std::pow(double(kAlbedo), kFurnaceDepth)) / (1 - kAlbedo)));
          }};
}

ClosedForm glassInFurnace() {
  return {"GlassInFurnace", R"(<scene version="3.0.0">
  <sensor type="perspective"><float name="fov" value="40"/>
    <transform name="to_world"><lookat origin="0.3,0.2,3.5" target="0,0,0" up="0,1,0"/></transform>
    <film type="hdrfilm"><integer name="width" value="30"/><integer name="height" value="20"/>
      <rfilter type="box"/></film></sensor>
  <shape type="sphere"><float name="radius" value="1"/>
    <bsdf type="dielectric"><float name="int_ior" value="1.5"/></bsdf></shape>
  <emitter type="constant"><rgb name="radiance" value="1"/></emitter></scene>)",
          -1, [](Vec3, Vec3) { return Color(1.0f); }};
}

struct Sampler {
  std::string name;
  unsigned scenes;  // the Scenes it can render completely
  std::function<void(RenderSettings&)> configure;
};

RenderSettings bdptAlone(RenderSettings s, int onlyS, int onlyT) {
  s.integrator = "bdpt";
  bdptOf(s).onlyS = onlyS;
  bdptOf(s).onlyT = onlyT;
  bdptOf(s).unweighted = true;
  return s;
}

void chains(RenderSettings& s, const char* integrator, SeedSampler seeds) {
  s.integrator = integrator;
  s.spp = 4;
  chainOf(s).seeds = seeds;
  chainOf(s).mutationsPerPixel = 64;
}

const std::vector<Sampler>& samplers() {
  static const std::vector<Sampler> all = {
      {"Path", 15, [](RenderSettings& s) { s.integrator = "path", s.spp = 64; }},
      {"Direct", kSphereLight | kRectangleLight, [](RenderSettings& s) { s.integrator = "direct", s.spp = 64; }},
      {"Bdpt", 15, [](RenderSettings& s) { s.integrator = "bdpt", s.spp = 16; }},
      {"PathTracingAlone", 15, [](RenderSettings& s) { s = bdptAlone(s, 0, -1), s.spp = 64; }},
      {"NextEventAlone", kSphereLight | kRectangleLight, [](RenderSettings& s) { s = bdptAlone(s, 1, -1), s.spp = 64; }},
      {"LightTracingAlone", kSphereLight | kRectangleLight | kClosedFurnace,
       [](RenderSettings& s) { s = bdptAlone(s, -1, 1), s.spp = 64; }},
      {"ErptPathSeeds", 15, [](RenderSettings& s) { chains(s, "erpt", SeedSampler::Path); }},
      {"ErptBdptSeeds", 15, [](RenderSettings& s) { chains(s, "erpt", SeedSampler::Bdpt); }},
      {"ErptBidirectionalMutation", 15,
       [](RenderSettings& s) {
         chains(s, "erpt", SeedSampler::Path);
         chainOf(s).bidirectionalMutation = 0.5f;
       }},
      {"PmcErPathSeeds", 15,
       [](RenderSettings& s) {
         chains(s, "pmc-er", SeedSampler::Path);
         pmcOf(s).population = 500;
       }},
      {"PmcErBdptSeeds", 15,
       [](RenderSettings& s) {
         chains(s, "pmc-er", SeedSampler::Bdpt);
         pmcOf(s).population = 500;
       }},
      {"MltPathSeeds", 15,
       [](RenderSettings& s) {
         chains(s, "mlt", SeedSampler::Path);
         s.spp = 1;
         mltOf(s).bootstrapSpp = 4;
       }},
      {"Pssmlt", 15,
       [](RenderSettings& s) {
         chains(s, "pssmlt", SeedSampler::Path);
         s.spp = 1;
         chainOf(s).directSamples = -1;
         mltOf(s).bootstrapSpp = 4;
       }},
      {"PssmltBdptDirectPass", 15,
       [](RenderSettings& s) {
         chains(s, "pssmlt", SeedSampler::Bdpt);
         s.spp = 1;
         chainOf(s).directSamples = 4;
         mltOf(s).bootstrapSpp = 4;
       }},
      {"Mmlt", kSphereLight | kRectangleLight | kClosedFurnace,  // bounded path lengths only
       [](RenderSettings& s) {
         s.integrator = "mmlt", s.spp = 1;
         chainOf(s).mutationsPerPixel = 64;
         mltOf(s).bootstrapSpp = 4;
       }},
      {"MltBdptSeeds", 15,
       [](RenderSettings& s) {
         chains(s, "mlt", SeedSampler::Bdpt);
         s.spp = 1;
         mltOf(s).bootstrapSpp = 4;
       }},
  };
  return all;
}

const std::vector<std::pair<unsigned, ClosedForm (*)()>>& closedForms() {
  static const std::vector<std::pair<unsigned, ClosedForm (*)()>> all = {
      {kSphereLight, sphereLight}, {kRectangleLight, rectangleLight}, {kClosedFurnace, closedFurnace},
      {kGlassInFurnace, glassInFurnace}};
  return all;
}

struct Case {
  size_t sampler, form;
};

std::vector<Case> cases() {
  std::vector<Case> out;
  for (size_t s = 0; s < samplers().size(); ++s)
    for (size_t f = 0; f < closedForms().size(); ++f)
      if (samplers()[s].scenes & closedForms()[f].first) out.push_back({s, f});
  return out;
}

class StatisticalClosedForm : public ::testing::TestWithParam<Case> {};

TEST_P(StatisticalClosedForm, MatchesBlockByBlock) {
  const Sampler& sampler = samplers()[GetParam().sampler];
  const ClosedForm form = closedForms()[GetParam().form].second();
  test::TempDir dir;
  const Scene scene = loadScene(dir.write("s.xml", form.xml));
  RenderSettings s;
  s.maxDepth = form.maxDepth;
  sampler.configure(s);
  const RgbImage exact = test::exactImage(scene, kWidth, kHeight, 8, form.radiance);
  const test::ClosedFormResult r =
      test::compareWithClosedForm(scene, s, exact, kRuns, 47000 + 100 * GetParam().sampler, kBlock);
  std::printf("%s on %s: ratio %.5f +- %.5f, %d blocks: mean z^2 %.2f, worst |z| %.2f\n", sampler.name.c_str(),
              form.name.c_str(), r.ratio, r.ratioError, r.blocks, r.meanSquare, r.worst);
  EXPECT_EQ(r.blocks, (kWidth / kBlock) * (kHeight / kBlock));
  // 24 runs: Student's t with 23 degrees of freedom. |t| > 5 has probability 5e-5, > 6 4e-6.
  EXPECT_LT(std::abs(r.ratio - 1), 5 * r.ratioError) << "whole image";
  EXPECT_LT(r.worst, 6.0) << "worst block";
}

std::string caseName(const ::testing::TestParamInfo<Case>& info) {
  return samplers()[info.param.sampler].name + "On" + closedForms()[info.param.form].second().name;
}

INSTANTIATE_TEST_SUITE_P(StatisticalTable, StatisticalClosedForm, ::testing::ValuesIn(cases()), caseName);

// The issue's precision bar for the integrators that do direct lighting by next-event
// estimation with the sphere's cone sampling: the whole image within 0.15% of the closed form.
// (Shadow rays that kept the direction between the unpushed points counted the sphere as
// occluding itself near its silhouette: 0.45-0.55% dark at coordinates near 1, 16% at 5.)
TEST(StatisticalClosedFormPrecision, SphereLightOverPlaneWithinAPermille) {
  const ClosedForm form = sphereLight();
  test::TempDir dir;
  const Scene scene = loadScene(dir.write("s.xml", form.xml));
  const RgbImage exact = test::exactImage(scene, kWidth, kHeight, 8, form.radiance);
  for (const char* integrator : {"path", "direct", "bdpt"}) {
    RenderSettings s;
    s.integrator = integrator;
    s.maxDepth = 2;
    s.spp = 512;
    const test::ClosedFormResult r = test::compareWithClosedForm(scene, s, exact, 16, 48000, kBlock);
    std::printf("%s: ratio %.5f +- %.5f\n", integrator, r.ratio, r.ratioError);
    EXPECT_LT(r.ratioError, 0.0004) << integrator;  // the bound below is then at least 3.75 of these (measured 0.0002)
    EXPECT_NEAR(r.ratio, 1.0, 0.0015) << integrator;
  }
}

}  // namespace
}  // namespace erpt
