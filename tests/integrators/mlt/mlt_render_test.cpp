// MLT in whole renders: against the references (channel means, error falling with work) and
// against the path tracer block by block; deterministic for any thread count. A chain alone is
// only consistent, but a render is unbiased in expectation (b and the chains' start states
// come from one bootstrap; docs/mlt.md), so renders from independent seeds are compared as
// unbiased estimators.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "erpt/erpt_settings.h"
#include "erpt/mlt_settings.h"
#include "erpt/image_io.h"
#include "erpt/render.h"
#include "erpt/scene_loader.h"
#include "support/block_bias.h"
#include "support/cornell_references.h"
#include "support/image_stats.h"
#include "support/in_place_reasons.h"
#include "support/test_support.h"

namespace erpt {
namespace {

RenderSettings mltSettings(int mutationsPerPixel) {
  RenderSettings s;
  s.integrator = "mlt";
  s.spp = 1;
  chainOf(s).mutationsPerPixel = mutationsPerPixel;
  return s;
}

using test::renderImage;

Scene defaultScene() { return loadScene(test::sourceDir() + "/scenes/default/scene.xml"); }

// One and two threads give the same image, with MLT's defaults and with the bidirectional
// mutation (its own stage and random stream; image 45x33); returns the one-thread render's
// statistics.
RenderStats expectSameImageForAnyThreadCount(RenderSettings s) {
  const Scene scene = defaultScene();
  s.threads = 1;
  RenderStats one;
  const RgbImage a = renderImage(scene, s, &one);
  s.threads = 2;
  test::expectBitIdentical(a, renderImage(scene, s));
  return one;
}

TEST(Mlt, SameImageForAnyThreadCount) {
  RenderSettings s = mltSettings(16);
  s.width = s.height = 32;
  chainOf(s).directSamples = 2;
  mltOf(s).chains = 300;
  mltOf(s).bootstrapSpp = 4;
  const RenderStats one = expectSameImageForAnyThreadCount(s);
  // Both kinds of move happened, and the chains did all the work asked of them.
  EXPECT_GT(chainStatsOf(one).accepted[size_t(MutationKind::LargeStep)], 0u);
  EXPECT_GT(chainStatsOf(one).accepted[size_t(MutationKind::Lens)], 0u);
  EXPECT_EQ(mltStatsOf(one).chains, 300u);
  EXPECT_EQ(chainStatsOf(one).mutations, mltStatsOf(one).chains * mltStatsOf(one).chainLength);

  s.width = 45;
  s.height = 33;
  chainOf(s).bidirectionalMutation = 0.5f;
  const RenderStats bidirectional = expectSameImageForAnyThreadCount(s);
  EXPECT_GT(chainStatsOf(bidirectional).accepted[size_t(MutationKind::Bidirectional)], 0u);
}

// The Cornell box at 128x128 (box filter) with MLT's defaults: channel means within 1% of
// Tungsten's render, and the relative MSE against the 128x128 reference falling about 4x for
// 4x the mutations (measured: 0.0106 -> 0.0034).
TEST(StatisticalMlt, CornellBoxMatchesReferences) {
  const Scene scene = test::cornellBox();
  RenderSettings low = mltSettings(32);
  low.width = low.height = 128;
  low.filterSet = true;
  low.filter = FilterKind::Box;
  low.seed = 1;
  RenderSettings high = low;
  chainOf(high).mutationsPerPixel = 128;
  high.seed = 2;
  RenderStats stats;
  const RgbImage a = renderImage(scene, low), b = renderImage(scene, high, &stats);
  test::expectCornellBoxConverges(a, b, 2.5, 6.0);
  EXPECT_GT(chainStatsOf(stats).accepted[size_t(MutationKind::LargeStep)], 0u);
}

// Block by block (support/block_bias.h): 16 MLT renders of 64x64 against 16 path-traced ones
// of 128 spp. The default scene, with MLT's defaults (large steps, lens perturbations and
// caustic perturbations through the glass sphere; direct light by the direct pass). Each
// render's image scales with its bootstrap's b, whose caustic paths are rare and bright: with
// 4 bootstrap spp the per-render block means were heavy-tailed (mean z^2 1.55 and 1.60 for
// 16 and 24 renders, 0.88 for 48); with 16 spp measured 0.97, worst |z| 2.40.
TEST(StatisticalMlt, DefaultSceneMatchesPathTracerBlockByBlock) {
  RenderSettings s = mltSettings(128);
  chainOf(s).directSamples = 8;
  mltOf(s).bootstrapSpp = 16;
  test::expectMatchesPathTracerBlockByBlock(defaultScene(), s, 16, 7000);
}

// Stationarity of the large step alone: with every step a large step and every path held by
// the chains (no direct pass), the chains are an independence sampler whose stationary
// distribution must be the image. A wrong W (a missing P(n), a technique's share, a roulette
// factor) moves energy between path lengths, so between lit and shadowed regions (with P(n)
// dropped: mean z^2 146). Chains that only take large steps stay on a path for many steps, so
// their block means are heavy-tailed: 48 renders of 64 mutations per pixel (measured: 1.29,
// worst |z| 2.41); 24 renders of 128 passed with 1.37 and 3.22 on one seed set and failed
// with 1.75 and 4.92 on another (the seed store's order changed).
TEST(StatisticalMlt, LargeStepsAloneMatchPathTracerBlockByBlock) {
  RenderSettings s = mltSettings(64);
  chainOf(s).directSamples = -1;
  mltOf(s).largeStepProbability = 1;
  mltOf(s).bootstrapSpp = 16;
  test::expectMatchesPathTracerBlockByBlock(test::cornellBox(), s, 48, 7100);
}

// Stationarity of Veach's bidirectional mutation alone: no large steps, no perturbations; the
// chains start at the bootstrap's paths and move only by deleting and regenerating subpaths
// (lengths, light points and film positions change), so the image is right only if its
// acceptance ratio is (docs/bidirectional-mutation.md).
TEST(StatisticalMlt, BidirectionalMutationAloneMatchesPathTracerBlockByBlock) {
  RenderSettings s = mltSettings(128);
  chainOf(s).directSamples = -1;
  chainOf(s).bidirectionalMutation = 1;
  mltOf(s).largeStepProbability = 0;
  mltOf(s).bootstrapSpp = 16;
  test::expectMatchesPathTracerBlockByBlock(test::cornellBox(), s, 16, 7400);
}

// The same through specular vertices: the default scene's glass and mirror spheres, with
// MLT's large steps and perturbations beside the bidirectional mutation.
TEST(StatisticalMlt, DefaultSceneWithBidirectionalMutationMatchesPathTracerBlockByBlock) {
  RenderSettings s = mltSettings(128);
  chainOf(s).directSamples = 8;
  chainOf(s).bidirectionalMutation = 0.5f;
  mltOf(s).bootstrapSpp = 16;
  test::expectMatchesPathTracerBlockByBlock(defaultScene(), s, 16, 7500);
}

// Plastic walls (a Dirac coat over a diffuse base at one vertex): paths through the coat are
// outside the chains' paths (f = 0 in the lens measure) and must reach the image through the
// bootstrap's in-place deposits, exactly once. Measured: mean z^2 0.62, worst |z| 1.66.
TEST(StatisticalMlt, PlasticBoxMatchesPathTracerBlockByBlock) {
  RenderSettings s = mltSettings(128);
  chainOf(s).directSamples = -1;
  mltOf(s).bootstrapSpp = 16;
  test::expectMatchesPathTracerBlockByBlock(loadScene(test::sourceDir() + "/tests/data/plastic-box.xml"), s, 16, 7200);
}

// Contributions the chains cannot hold are deposited in place and counted by reason: under a
// directional light (tests/data/directional.xml) many are, for that reason, and the reasons
// add up to the total the summary gives.
TEST(Mlt, SeedsInPlaceAreCountedByReason) {
  test::expectInPlaceReasonsAddUp(mltSettings(4), [](const RenderStats& st) { return mltStatsOf(st).inPlaceSeeds; }, 50u);
}

}  // namespace
}  // namespace erpt
