// PSSMLT in whole renders: against the Cornell box's references, against the path tracer
// block by block (with and without large steps), the same image for any thread count, and
// its refusals. Its closed-form cases are in closed_forms_test.cpp. A render is unbiased in
// expectation up to b's estimate, whose error is a factor common to all pixels (docs/pssmlt.md).
#include <gtest/gtest.h>

#include "erpt/chain_options.h"
#include "erpt/error.h"
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

RenderSettings pssmltSettings(int mutationsPerPixel) {
  RenderSettings s;
  s.integrator = "pssmlt";
  s.spp = 1;
  chainOf(s).mutationsPerPixel = mutationsPerPixel;
  return s;
}

using test::renderImage;

Scene defaultScene() { return loadScene(test::sourceDir() + "/scenes/default/scene.xml"); }

// 45x33 (not a multiple of anything), 300 chains: a whole group and a part of one; over the
// path tracer and over BDPT.
class PssmltThreads : public ::testing::TestWithParam<SeedSampler> {};

TEST_P(PssmltThreads, SameImageForAnyThreadCount) {
  const Scene scene = defaultScene();
  RenderSettings s = pssmltSettings(16);
  chainOf(s).seeds = GetParam();
  s.width = 45;
  s.height = 33;
  mltOf(s).chains = 300;
  mltOf(s).bootstrapSpp = 2;
  s.threads = 1;
  RenderStats one;
  const RgbImage a = renderImage(scene, s, &one);
  s.threads = 2;
  test::expectBitIdentical(a, renderImage(scene, s));
  const PssmltStats& p = pssmltStatsOf(one);
  EXPECT_EQ(p.chains, 300u);
  EXPECT_EQ(p.smallSteps + p.largeSteps, p.chains * p.chainLength) << "every chain took every step";
  EXPECT_GE(p.chains * p.chainLength, 16u * 45 * 33);
  EXPECT_GT(p.smallAccepted, 0u);
  EXPECT_GT(p.largeAccepted, 0u);
  EXPECT_EQ(p.bootstrapSamples, 2u * 45 * 33);
}

INSTANTIATE_TEST_SUITE_P(Pssmlt, PssmltThreads, ::testing::Values(SeedSampler::Path, SeedSampler::Bdpt),
                         [](const auto& info) { return std::string(info.param == SeedSampler::Path ? "Path" : "Bdpt"); });

TEST(Pssmlt, RefusesChainsItCannotHold) {
  RenderSettings s = pssmltSettings(16);
  s.width = s.height = 16;
  mltOf(s).chains = (1 << 20) + 1;
  const Scene scene = defaultScene();
  RenderStats stats;
  EXPECT_THROW(render(scene, resolveSettings(scene, s), stats), UsageError);
}

// The Cornell box at 128x128 (box filter): channel means within 1% of Tungsten's render, and
// the relative MSE against the 128x128 reference falling about 4x for 4x the steps. The image
// scales with b, whose relative error with the default bootstrap (7 samples per pixel) is
// about 1.8% here (the light, seen directly, is most of a sample's variance): 64 samples per
// pixel make it about 0.6%.
TEST(StatisticalPssmlt, CornellBoxMatchesReferences) {
  const Scene scene = test::cornellBox();
  RenderSettings low = pssmltSettings(32);
  chainOf(low).directSamples = -1;
  mltOf(low).bootstrapSpp = 64;
  low.width = low.height = 128;
  low.filterSet = true;
  low.filter = FilterKind::Box;
  low.seed = 1;
  RenderSettings high = low;
  chainOf(high).mutationsPerPixel = 128;
  high.seed = 2;
  test::expectCornellBoxConverges(renderImage(scene, low), renderImage(scene, high), 2.5, 6.0);
}

// Block by block against the path tracer on the default scene (a glass sphere's caustic, paths
// through the glass, direct and indirect light all in the chains).
TEST(StatisticalPssmlt, DefaultSceneMatchesPathTracerBlockByBlock) {
  RenderSettings s = pssmltSettings(128);
  chainOf(s).directSamples = -1;
  mltOf(s).bootstrapSpp = 16;
  test::expectMatchesPathTracerBlockByBlock(defaultScene(), s, 16, 8100);
}

// The same with the direct pass (paths of one and two segments apart, 8 samples per pixel) and
// over BDPT: its light tracing splats elsewhere than the camera sample, so a chain's sample
// is several deposits.
TEST(StatisticalPssmlt, DirectPassAndBdptMatchPathTracerBlockByBlock) {
  RenderSettings s = pssmltSettings(64);
  chainOf(s).directSamples = 8;
  chainOf(s).seeds = SeedSampler::Bdpt;
  mltOf(s).bootstrapSpp = 8;
  test::BlockTestOptions options;
  options.referenceSpp = 512;  // at 128 the reference was half of the z denominators
  test::expectMatchesPathTracerBlockByBlock(defaultScene(), s, 16, 8300, options);
}

// Small steps alone (no large step): what keeps the chains' distribution is then the small
// step's symmetry (and the fresh draws of the numbers a path did not read). An offset whose
// sign leans one way (5:3) drifts the chains across the image: mean z^2 862.
TEST(StatisticalPssmlt, SmallStepsAloneMatchPathTracerBlockByBlock) {
  RenderSettings s = pssmltSettings(128);
  chainOf(s).directSamples = -1;
  mltOf(s).largeStepProbability = 0;
  mltOf(s).bootstrapSpp = 16;
  test::expectMatchesPathTracerBlockByBlock(test::cornellBox(), s, 16, 8200);
}

}  // namespace
}  // namespace erpt
