// The wavefront path tracer against references and closed-form answers.
#include <gtest/gtest.h>

#include "erpt/render.h"
#include "erpt/scene_loader.h"
#include "core/seeds.h"
#include "support/image_stats.h"
#include "support/test_support.h"

namespace erpt {
namespace {

using test::meanOf;
using test::TempDir;

RgbImage renderPathImage(const Scene& scene, int spp, int size, uint64_t seed = 1, int threads = 0) {
  RenderSettings s;
  s.integrator = "path";
  s.spp = spp;
  s.seed = seed;
  s.threads = threads;
  if (size > 0) s.width = s.height = size;
  s.filterSet = true;
  s.filter = FilterKind::Box;
  RenderStats stats;
  RgbImage img = render(scene, s, stats);
  EXPECT_EQ(stats.invalidSamples, 0u);
  return img;
}

// Channel means within 1% of the Tungsten reference, and relative MSE against the 128x128
// box-filtered Mitsuba reference falling as 1/spp (x4 samples: factor 3.2-4.8), i.e. no bias
// floor.
TEST(StatisticalPath, CornellBoxMatchesReferences) {
  const std::string dir = test::sharedScenesDir() + "/cornell-box";
  Scene scene = loadScene(dir + "/scene.xml");
  RgbImage tungsten = readImage(dir + "/TungstenRender.exr");
  RgbImage ref128 = readImage(dir + "/reference-box-128.exr");
  RgbImage low = renderPathImage(scene, 64, 128, 7);
  RgbImage high = renderPathImage(scene, 256, 128, 8);
  Color m = meanOf(high), r = meanOf(tungsten);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(m[c] / r[c], 1.0, 0.01) << "channel " << c;
  double e64 = test::relativeMse(low, ref128), e256 = test::relativeMse(high, ref128);
  std::printf("relMSE 64 spp %.3g, 256 spp %.3g, ratio %.2f; means %.4f %.4f %.4f vs %.4f %.4f %.4f\n", e64, e256,
              e64 / e256, m.x, m.y, m.z, r.x, r.y, r.z);
  EXPECT_GT(e64 / e256, 3.2);
  EXPECT_LT(e64 / e256, 4.8);
}

// Closed diffuse sphere, inner side emitting Le with albedo a: L = Le / (1 - a) everywhere.
TEST(StatisticalPath, FurnaceSphere) {
  TempDir dir;
  Scene scene = loadScene(dir.write("s.xml", R"(<scene version="3.0.0">
    <sensor type="perspective"><float name="fov" value="70"/>
      <transform name="to_world"><lookat origin="0.1,0.2,0" target="1,0.3,0.2" up="0,1,0"/></transform>
      <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="16"/></film></sensor>
    <shape type="sphere"><boolean name="flip_normals" value="true"/>
      <bsdf type="diffuse"><rgb name="reflectance" value="0.5, 0.8, 0.2"/></bsdf>
      <emitter type="area"><rgb name="radiance" value="1, 0.5, 2"/></emitter></shape>
  </scene>)"));
  Color m = meanOf(renderPathImage(scene, 256, 0));
  EXPECT_NEAR(m.x / (1.0f / 0.5f), 1.0f, 0.01f);
  EXPECT_NEAR(m.y / (0.5f / 0.2f), 1.0f, 0.015f);
  EXPECT_NEAR(m.z / (2.0f / 0.8f), 1.0f, 0.01f);
}

// Lossless specular objects in a uniform environment of radiance Le: every path leaves
// again, carrying Le (glass: the eta^2 radiance scaling in and out cancels).
TEST(StatisticalPath, GlassAndMirrorInUniformEnvironment) {
  TempDir dir;
  Scene scene = loadScene(dir.write("s.xml", R"(<scene version="3.0.0">
    <sensor type="perspective"><float name="fov" value="40"/>
      <transform name="to_world"><lookat origin="0,0,4" target="0,0,0" up="0,1,0"/></transform>
      <film type="hdrfilm"><integer name="width" value="24"/><integer name="height" value="24"/></film></sensor>
    <shape type="sphere"><point name="center" value="-0.6, 0, 0"/><float name="radius" value="0.5"/>
      <bsdf type="dielectric"><float name="int_ior" value="1.5"/></bsdf></shape>
    <shape type="sphere"><point name="center" value="0.6, 0, 0"/><float name="radius" value="0.5"/>
      <bsdf type="conductor"><string name="material" value="none"/></bsdf></shape>
    <emitter type="constant"><rgb name="radiance" value="0.7, 0.3, 1.2"/></emitter>
  </scene>)"));
  RgbImage img = renderPathImage(scene, 64, 0);
  Color m = meanOf(img);
  EXPECT_NEAR(m.x, 0.7f, 0.007f);
  EXPECT_NEAR(m.y, 0.3f, 0.003f);
  EXPECT_NEAR(m.z, 1.2f, 0.012f);
}

// 64x64 at 16 spp is four tasks' chunks of 16,384 samples, so two threads share the batch
// (at 40x40 x 4 spp one task traced everything and a shared wavefront went unnoticed).
TEST(Path, SameSeedSameImageForAnyThreadCount) {
  Scene scene = loadScene(test::sourceDir() + "/scenes/default/scene.xml");
  RgbImage one = renderPathImage(scene, 16, 64, 5, 1);
  RgbImage two = renderPathImage(scene, 16, 64, 5, 2);
  ASSERT_EQ(one.pixels.size(), two.pixels.size());
  for (size_t i = 0; i < one.pixels.size(); ++i)
    ASSERT_TRUE(one.pixels[i].x == two.pixels[i].x && one.pixels[i].y == two.pixels[i].y &&
                one.pixels[i].z == two.pixels[i].z)
        << "pixel " << i;
}

// Path regeneration. Rendering, every task traces its chunk of samples in a wavefront of 4,096
// paths in flight, whose ended paths' slots start the next samples; recording seeds, one
// wavefront of the whole batch starts every sample at once and drains. Each sample's radiance
// depends only on its index and the film adds them in sample order, so both give the same image
// bit for bit, for both films and any thread count; a sample lost, traced twice or filed under
// another index by the refills would change it. (6,400 samples: the 4,096 slots refill once or more.)
TEST(Path, RegeneratingWavefrontsGiveTheDrainedWavefrontsImage) {
  Scene scene = loadScene(test::sourceDir() + "/scenes/default/scene.xml");
  for (FilmMode film : {FilmMode::Fis, FilmMode::Splat}) {
    auto renderWith = [&](bool recordSeeds, int threads) {
      RenderSettings s;
      s.integrator = "path";
      s.spp = 4;
      s.width = s.height = 40;
      s.seed = 9;
      s.threads = threads;
      s.film = film;
      s.filterSet = true;
      s.filter = FilterKind::Tent;
      SeedStore seeds;
      if (recordSeeds) s.seeds = &seeds;
      RenderStats stats;
      RgbImage img = render(scene, s, stats);
      EXPECT_EQ(stats.samples, 40u * 40u * 4u);
      EXPECT_EQ(recordSeeds, seeds.size() > 0);
      return img;
    };
    const RgbImage drained = renderWith(true, 2), one = renderWith(false, 1), two = renderWith(false, 2);
    ASSERT_EQ(drained.pixels.size(), one.pixels.size());
    for (size_t i = 0; i < drained.pixels.size(); ++i)
      for (int c = 0; c < 3; ++c) {
        ASSERT_EQ(one.pixels[i][c], drained.pixels[i][c]) << "pixel " << i << ", film mode " << int(film);
        ASSERT_EQ(two.pixels[i][c], drained.pixels[i][c]) << "pixel " << i << ", film mode " << int(film);
      }
  }
}

TEST(Path, MaxDepthOneSeesOnlyEmitters) {
  Scene scene = loadScene(test::sharedScenesDir() + "/cornell-box/scene.xml");
  RenderSettings s;
  s.integrator = "path";
  s.spp = 1;
  s.width = s.height = 32;
  s.maxDepth = 1;
  // One sample per pixel, each counted in its own pixel only (a splatting film would blend
  // the light's edge into its neighbours).
  s.film = FilmMode::Fis;
  RenderStats stats;
  RgbImage img = render(scene, s, stats);
  int lit = 0;
  for (const Color& c : img.pixels) {
    EXPECT_TRUE(isBlack(c) || c.x > 0.5f);  // emitter (17, 12, 4) or nothing
    lit += !isBlack(c);
  }
  EXPECT_GT(lit, 0);
}

}  // namespace
}  // namespace erpt
