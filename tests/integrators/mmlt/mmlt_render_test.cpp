// mmlt in whole renders: the same image for any thread count, block by block against the path
// tracer at the same longest path (a glass sphere's caustic and a mirror), with and without
// large steps. Its closed-form cases are in closed_forms_test.cpp.
#include <gtest/gtest.h>

#include "erpt/chain_options.h"
#include "erpt/mlt_settings.h"
#include "erpt/pssmlt_settings.h"
#include "erpt/render.h"
#include "erpt/scene_loader.h"
#include "support/block_bias.h"
#include "support/cornell_references.h"
#include "support/image_stats.h"
#include "support/test_support.h"

namespace erpt {
namespace {

RenderSettings mmltSettings(int mutationsPerPixel) {
  RenderSettings s;
  s.integrator = "mmlt";
  s.spp = 1;
  s.maxDepth = 6;
  chainOf(s).mutationsPerPixel = mutationsPerPixel;
  return s;
}

Scene defaultScene() { return loadScene(test::sourceDir() + "/scenes/default/scene.xml"); }

// 45x33, 300 chains: a whole group and a part of one.
TEST(Mmlt, SameImageForAnyThreadCount) {
  const Scene scene = defaultScene();
  RenderSettings s = mmltSettings(16);
  s.width = 45;
  s.height = 33;
  mltOf(s).chains = 300;
  mltOf(s).bootstrapSpp = 4;
  s.threads = 1;
  RenderStats one;
  const RgbImage a = test::renderImage(scene, s, &one);
  s.threads = 2;
  test::expectBitIdentical(a, test::renderImage(scene, s));
  const PssmltStats& p = pssmltStatsOf(one);
  EXPECT_EQ(p.smallSteps + p.largeSteps, p.chains * p.chainLength);
  EXPECT_GT(p.smallAccepted, 0u);
  EXPECT_GT(p.largeAccepted, 0u);
}

// --max-depth 0 means no path at all, as for every integrator (6 segments is only the default
// of an unbounded depth).
TEST(Mmlt, MaxDepthZeroRendersNothing) {
  RenderSettings s = mmltSettings(4);
  s.width = 19;
  s.height = 13;
  s.maxDepth = 0;
  const RgbImage image = test::renderImage(defaultScene(), s);
  ASSERT_EQ(image.pixels.size(), 19u * 13u);
  for (const Color& c : image.pixels) ASSERT_TRUE(c.x == 0 && c.y == 0 && c.z == 0);
}

// Block by block against the path tracer, paths of up to 6 segments: every length's chains
// and every strategy, weighted by the number of strategies. With 2048 chains the block means
// were heavy-tailed (mean z^2 1.5-1.8 with 16 renders); 8192 shorter chains and 24 renders.
TEST(StatisticalMmlt, DefaultSceneMatchesPathTracerBlockByBlock) {
  RenderSettings s = mmltSettings(128);
  mltOf(s).bootstrapSpp = 16;
  mltOf(s).chains = 8192;
  test::expectMatchesPathTracerBlockByBlock(defaultScene(), s, 24, 8400);
}

// Small steps alone: the chains keep their path length and move their strategy only by small
// steps of its number.
TEST(StatisticalMmlt, SmallStepsAloneMatchPathTracerBlockByBlock) {
  RenderSettings s = mmltSettings(128);
  mltOf(s).largeStepProbability = 0;
  mltOf(s).bootstrapSpp = 16;
  mltOf(s).chains = 8192;
  test::expectMatchesPathTracerBlockByBlock(test::cornellBox(), s, 24, 8500);
}

}  // namespace
}  // namespace erpt
