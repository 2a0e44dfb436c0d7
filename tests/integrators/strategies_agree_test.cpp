// Strategies check each other where no closed form exists: light tracing alone (BDPT's t = 1),
// path tracing alone (s = 0: camera paths that hit a light) and next-event estimation alone
// (s = 1), each unweighted (--bdpt-weights none), estimate every path they can make. On a scene
// where each makes every path (the camera sees no Dirac surface; a light that can be hit), they
// must agree block by block. The two sides of each comparison share no transport code: light
// tracing walks from the light with the adjoint BSDF and splats through the camera's
// importance; path tracing walks from the camera with the BSDF and ends on an emitter.
//
// The table covers the Dirac lobes the light walk has to turn into importance transport
// (refraction at unequal angles around a light inside glass; a coating's two mirror lobes over
// a conductor; a blend of a conductor's and a dielectric's reflections; plastic), the smooth
// BSDFs seen directly, and every light type (area triangles and spheres, point, spot,
// directional, constant environment).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "erpt/bdpt_settings.h"
#include "erpt/render.h"
#include "erpt/scene_loader.h"
#include "support/block_bias.h"
#include "support/environment_scene.h"
#include "support/image_stats.h"
#include "support/test_support.h"

namespace erpt {
namespace {

// BDPT's strategies alone, and the path tracer (`path`: its own stages and vector kernels,
// next-event estimation and BSDF sampling weighted by MIS), which they check.
enum Strategy { kLightTracing, kPathTracing, kNextEvent, kPathIntegrator };
const char* strategyName(Strategy s) {
  return s == kLightTracing ? "light tracing"
         : s == kPathTracing ? "path tracing"
         : s == kNextEvent   ? "next event"
                             : "the path tracer";
}

// 24 runs a side: Welch's z is then close to normal (about 46 degrees of freedom), so mean z^2
// is about 1.05 with a standard deviation of 0.27 over 30 blocks, and |z| > 5 in one of 30
// blocks has a chance of about 1e-5.
constexpr int kRuns = 24;

std::vector<RgbImage> renders(const Scene& scene, Strategy strategy, int spp, uint64_t seed) {
  RenderSettings s;
  s.integrator = strategy == kPathIntegrator ? "path" : "bdpt";
  s.width = 48, s.height = 40;  // not powers of two
  s.filterSet = true;
  s.filter = FilterKind::Box;
  s.spp = spp;
  if (strategy != kPathIntegrator) bdptOf(s).unweighted = true;
  if (strategy == kLightTracing) bdptOf(s).onlyT = 1;
  if (strategy == kPathTracing) bdptOf(s).onlyS = 0;
  if (strategy == kNextEvent) bdptOf(s).onlyS = 1;
  std::vector<RgbImage> images;
  for (int k = 0; k < kRuns; ++k) {
    s.seed = seed + uint64_t(k);
    images.push_back(test::renderImage(scene, s));
  }
  return images;
}

struct Comparison {
  Strategy strategy;
  int spp;
};

// Renders the scene with each strategy and compares every later one with the first.
void expectStrategiesAgree(const std::string& xml, const std::vector<Comparison>& strategies, uint64_t seed) {
  test::TempDir dir;
  writeImageAtomic(dir.file("sky.exr"), test::skyImage());  // for scenes lit by the test sky
  const Scene scene = loadScene(dir.write("s.xml", xml));
  const std::vector<RgbImage> first = renders(scene, strategies[0].strategy, strategies[0].spp, seed);
  for (size_t k = 1; k < strategies.size(); ++k) {
    const std::vector<RgbImage> other = renders(scene, strategies[k].strategy, strategies[k].spp, seed + 1000 * k);
    const test::BlockZScores z = test::blockZScores(other, first, 8);
    // The whole image as one block too: a bias spread thinly over the image shows there first.
    const test::BlockZScores whole = test::blockZScores(other, first, 40);
    double a = 0, b = 0;
    for (const RgbImage& i : other) a += luminance(test::meanOf(i));
    for (const RgbImage& i : first) b += luminance(test::meanOf(i));
    std::printf("%s against %s: image means %.4f (z %.2f), blocks: mean z^2 %.2f, worst |z| %.2f over %zu\n",
                strategyName(strategies[k].strategy), strategyName(strategies[0].strategy), a / b, whole.worst,
                z.meanSquare, z.worst, z.z.size());
    EXPECT_GE(z.z.size(), 28u);  // of 30
    EXPECT_LT(z.meanSquare, 2.2) << strategyName(strategies[k].strategy);
    EXPECT_LT(z.worst, 5.0) << strategyName(strategies[k].strategy);
    EXPECT_LT(whole.worst, 4.5) << strategyName(strategies[k].strategy) << ": the image";
  }
}

// A room's floor and back wall, seen from the front (diffuse; the camera sees nothing else).
std::string room(const std::string& contents) {
  return R"(<scene version="3.0.0">
  <sensor type="perspective"><float name="fov" value="50"/>
    <transform name="to_world"><lookat origin="0,1.2,3.2" target="0,0.5,0" up="0,1,0"/></transform>
    <film type="hdrfilm"><integer name="width" value="48"/><integer name="height" value="40"/>
      <rfilter type="box"/></film></sensor>
  <shape type="rectangle"><transform name="to_world"><rotate x="1" angle="-90"/><scale value="3"/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.6, 0.5"/></bsdf></shape>
  <shape type="rectangle"><transform name="to_world"><scale value="3"/><translate y="1" z="-1.2"/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.4, 0.5, 0.6"/></bsdf></shape>)" +
         contents + "</scene>";
}

// A small sphere light inside a glass cube turned about two axes, above the camera's view: all
// its light leaves through refractions at unequal angles (the eta^2 of radiance transport must
// not enter importance transport: light tracing was 1 / 1.5^2 too dark).
TEST(StatisticalStrategies, LightInsideTurnedGlassCube) {
  expectStrategiesAgree(room(R"(
  <shape type="cube"><transform name="to_world"><scale value="0.3"/><rotate x="1" angle="30"/><rotate z="1" angle="20"/>
    <translate y="2.4" z="-0.2"/></transform>
    <bsdf type="dielectric"><float name="int_ior" value="1.5"/></bsdf></shape>
  <shape type="sphere"><point name="center" value="0, 2.4, -0.2"/><float name="radius" value="0.08"/>
    <emitter type="area"><rgb name="radiance" value="60"/></emitter></shape>)"),
                        {{kLightTracing, 16}, {kPathTracing, 64}}, 49000);
}

// A coated silver sphere (a smooth coat over a mirror: two Dirac lobes along one direction) and
// a blend of a conductor and a glass (their two reflections coincide), hanging above the view,
// lit from below by a large light behind the camera that faces up: the floor and the wall see
// that light only through the spheres (L S D E, and longer). Path tracing alone finds these
// paths only when a bounce off the floor meets a sphere and its reflection meets the light,
// hence its many samples. (Light tracing took a coated mirror's two lobes twice: image means
// 0.79 of path tracing's.)
TEST(StatisticalStrategies, CoincidentDiracLobes) {
  expectStrategiesAgree(room(R"(
  <shape type="sphere"><point name="center" value="-0.7, 3.0, 1.0"/><float name="radius" value="0.7"/>
    <bsdf type="coating"><float name="int_ior" value="1.5"/><bsdf type="conductor"><string name="material" value="Ag"/></bsdf></bsdf></shape>
  <shape type="sphere"><point name="center" value="0.9, 3.0, 1.0"/><float name="radius" value="0.6"/>
    <bsdf type="blendbsdf"><float name="weight" value="0.4"/>
      <bsdf type="conductor"><string name="material" value="Al"/></bsdf>
      <bsdf type="dielectric"><float name="int_ior" value="1.5"/></bsdf></bsdf></shape>
  <shape type="rectangle"><transform name="to_world"><scale value="3"/><rotate x="1" angle="-90"/><translate y="1.5" z="5.5"/></transform>
    <emitter type="area"><rgb name="radiance" value="1.5"/></emitter></shape>)"),
                        {{kLightTracing, 16}, {kPathTracing, 512}}, 49100);
}

// Smooth BSDFs seen directly (rough conductor, rough plastic, Phong, Ward, rough dielectric,
// rough coating over diffuse) and plastic's Dirac coat, lit by a sphere light (next-event
// estimation samples its cone): light tracing against next-event estimation (path tracing
// alone makes these paths too, and is compared with both on the scenes below).
TEST(StatisticalStrategies, SmoothBsdfsUnderASphereLight) {
  expectStrategiesAgree(room(R"(
  <shape type="sphere"><point name="center" value="-0.9, 0.3, 0.2"/><float name="radius" value="0.3"/>
    <bsdf type="roughconductor"><string name="material" value="Au"/><float name="alpha" value="0.3"/></bsdf></shape>
  <shape type="sphere"><point name="center" value="-0.25, 0.3, 0.2"/><float name="radius" value="0.3"/>
    <bsdf type="roughplastic"><float name="alpha" value="0.2"/><rgb name="diffuse_reflectance" value="0.2, 0.4, 0.7"/></bsdf></shape>
  <shape type="sphere"><point name="center" value="0.4, 0.3, 0.2"/><float name="radius" value="0.3"/>
    <bsdf type="phong"><float name="exponent" value="20"/><rgb name="diffuse_reflectance" value="0.4, 0.2, 0.1"/>
      <rgb name="specular_reflectance" value="0.3"/></bsdf></shape>
  <shape type="sphere"><point name="center" value="1.05, 0.3, 0.2"/><float name="radius" value="0.3"/>
    <bsdf type="ward"><float name="alpha_u" value="0.1"/><float name="alpha_v" value="0.3"/>
      <rgb name="diffuse_reflectance" value="0.3, 0.5, 0.2"/><rgb name="specular_reflectance" value="0.2"/></bsdf></shape>
  <shape type="sphere"><point name="center" value="-0.5, 0.25, 1.0"/><float name="radius" value="0.25"/>
    <bsdf type="roughdielectric"><float name="alpha" value="0.3"/><float name="int_ior" value="1.5"/></bsdf></shape>
  <shape type="sphere"><point name="center" value="0.15, 0.25, 1.0"/><float name="radius" value="0.25"/>
    <bsdf type="roughcoating"><float name="alpha" value="0.2"/>
      <bsdf type="diffuse"><rgb name="reflectance" value="0.6, 0.3, 0.3"/></bsdf></bsdf></shape>
  <shape type="sphere"><point name="center" value="0.8, 0.25, 2.3"/><float name="radius" value="0.25"/>
    <bsdf type="plastic"><rgb name="diffuse_reflectance" value="0.1, 0.5, 0.2"/></bsdf></shape>
  <shape type="sphere"><point name="center" value="0.3, 1.9, 0.8"/><float name="radius" value="0.15"/>
    <emitter type="area"><rgb name="radiance" value="40"/></emitter></shape>)"),
                        {{kLightTracing, 16}, {kNextEvent, 16}}, 49200);
}

// Lights no camera path can hit (a point light, a spot, a directional light), over diffuse and
// glossy surfaces without Dirac lobes: light tracing against next-event estimation.
TEST(StatisticalStrategies, DeltaLights) {
  expectStrategiesAgree(room(R"(
  <shape type="sphere"><point name="center" value="-0.4, 0.3, 0.4"/><float name="radius" value="0.3"/>
    <bsdf type="roughconductor"><string name="material" value="Cu"/><float name="alpha" value="0.25"/></bsdf></shape>
  <emitter type="point"><point name="position" value="0.6, 1.6, 1.2"/><rgb name="intensity" value="3"/></emitter>
  <emitter type="spot"><transform name="to_world"><lookat origin="-1, 2, 1" target="-0.3, 0, 0"/></transform>
    <rgb name="intensity" value="8"/><float name="cutoff_angle" value="25"/></emitter>
  <emitter type="directional"><vector name="direction" value="0.3, -1, -0.4"/><rgb name="irradiance" value="0.6"/></emitter>)"),
                        {{kNextEvent, 16}, {kLightTracing, 16}}, 49300);
}

// A constant environment (the light at infinity, emitted from a disk across the scene) through
// an open room: all three strategies.
TEST(StatisticalStrategies, ConstantEnvironment) {
  expectStrategiesAgree(room(R"(
  <shape type="sphere"><point name="center" value="0, 0.35, 0.5"/><float name="radius" value="0.35"/>
    <bsdf type="roughplastic"><float name="alpha" value="0.15"/><rgb name="diffuse_reflectance" value="0.5, 0.2, 0.2"/></bsdf></shape>
  <emitter type="constant"><rgb name="radiance" value="0.8, 0.9, 1.0"/></emitter>)"),
                        {{kPathTracing, 16}, {kNextEvent, 16}, {kLightTracing, 16}}, 49400);
}

// The test sky with its small sun through an open room, over a diffuse sphere: the path
// tracer's sampling of the map and lookups of escaping rays (in its vector kernels) against
// next-event estimation alone (BDPT's, which samples the map as LightSampler does), and that
// against light tracing alone.
TEST(StatisticalStrategies, EnvironmentMapInThePathTracer) {
  expectStrategiesAgree(room(R"(
  <shape type="sphere"><point name="center" value="0.3, 0.4, 0.3"/><float name="radius" value="0.4"/>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.3, 0.6, 0.3"/></bsdf></shape>
  <emitter type="envmap"><string name="filename" value="sky.exr"/><float name="scale" value="0.2"/>
    <transform name="to_world"><rotate y="1" angle="130"/></transform></emitter>)"),
                        {{kNextEvent, 64}, {kPathIntegrator, 64}, {kLightTracing, 16}}, 49500);
}

}  // namespace
}  // namespace erpt
