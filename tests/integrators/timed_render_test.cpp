// Time-budgeted rendering (RenderSettings::timeBudget, `erpt render --time`): passes of
// growing spp averaged by weight. No wall-clock limits are asserted here; the tests check
// what the passes add up to.
#include <gtest/gtest.h>

#include <map>

#include "erpt/erpt_settings.h"
#include "integrators/noise_filters.h"
#include "erpt/render.h"
#include "erpt/scene_loader.h"
#include "support/image_stats.h"
#include "support/test_support.h"

namespace erpt {
namespace {

Scene cornell() { return loadScene(test::sharedScenesDir() + "/cornell-box/scene.xml"); }

RenderSettings timed(const std::string& integrator, double seconds) {
  RenderSettings s;
  s.integrator = integrator;
  s.width = s.height = 32;
  s.filterSet = true;
  s.filter = FilterKind::Box;
  s.timeBudget = seconds;
  return s;
}

// Every pass reports the image so far; spp grows, the passes add up to the final spp, and the
// last report is the returned image. The averaged image is unbiased: its channel means match
// Tungsten's render within 2%.
TEST(TimedRender, PassesAddUpAndTheAverageIsUnbiased) {
  const Scene scene = cornell();
  RenderSettings s = timed("path", 1.0);
  std::vector<int> spp;
  std::vector<double> seconds;
  RgbImage last;
  s.onPass = [&](const RgbImage& img, double t, int n) {
    spp.push_back(n);
    seconds.push_back(t);
    last = img;
  };
  RenderStats stats;
  const RgbImage img = render(scene, s, stats);
  ASSERT_GE(spp.size(), 2u);
  EXPECT_EQ(int(spp.size()), stats.passes);
  EXPECT_EQ(spp.back(), stats.spp);
  EXPECT_EQ(stats.samples, uint64_t(stats.spp) * 32 * 32);
  for (size_t i = 1; i < spp.size(); ++i) {
    EXPECT_GT(spp[i], spp[i - 1]);
    EXPECT_GE(seconds[i], seconds[i - 1]);
  }
  EXPECT_EQ(last.pixels.size(), img.pixels.size());
  for (size_t i = 0; i < img.pixels.size(); ++i) ASSERT_EQ(last.pixels[i].x, img.pixels[i].x);
  const Color m = test::meanOf(img), r = test::meanOf(readImage(test::sharedScenesDir() + "/cornell-box/TungstenRender.exr"));
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(m[c] / r[c], 1.0, 0.02) << "channel " << c;
}

// ERPT under a budget keeps the configured mutations per seed in every pass: e_d comes from
// the configured spp, so the chains do M mutations per pixel per `spp` seeds per pixel. The
// proposed-mutations filter sees the sum of the passes' tallies, not one pass's.
TEST(TimedRender, ErptKeepsMutationsPerSeed) {
  const Scene scene = cornell();
  RenderSettings s = timed("erpt", 1.5);
  s.spp = 8;
  chainOf(s).mutationsPerPixel = 40;
  erptOf(s).chainLength = 20;
  chainOf(s).pmFilterRadius = 2;
  RenderStats stats;
  const RgbImage img = render(scene, s, stats);
  std::map<std::string, RgbImage> extra(stats.extraImages.begin(), stats.extraImages.end());
  ASSERT_EQ(extra.size(), 3u);
  double proposals = 0;
  for (const Color& c : extra["proposals"].pixels) proposals += c.x;
  EXPECT_GT(proposals, 0.5 * double(chainStatsOf(stats).mutations));
  EXPECT_LE(proposals, double(chainStatsOf(stats).mutations));
  const RgbImage refiltered = proposalFilteredImage(extra["raw"], extra["chains"], extra["proposals"], 2);
  for (size_t i = 0; i < img.pixels.size(); ++i) ASSERT_EQ(img.pixels[i].y, refiltered.pixels[i].y) << i;
  const double expected = double(stats.spp) / 8 * 40 * 32 * 32;
  EXPECT_NEAR(double(chainStatsOf(stats).mutations) / expected, 1.0, 0.15) << chainStatsOf(stats).mutations << " vs " << expected;
  const Color m = test::meanOf(img), r = test::meanOf(readImage(test::sharedScenesDir() + "/cornell-box/TungstenRender.exr"));
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(m[c] / r[c], 1.0, 0.05) << "channel " << c;
}

TEST(TimedRender, AbsurdBudgetsAreRejected) {
  const Scene scene = cornell();
  for (double t : {-1.0, 1e9, std::nan("")}) {
    RenderStats stats;
    EXPECT_THROW(render(scene, timed("path", t), stats), UsageError) << t;
  }
}

}  // namespace
}  // namespace erpt

namespace erpt {
namespace {

// The Embree scene is built before the render's clock starts: its time is reported apart
// (buildSeconds) and a render given a built one (RenderSettings::tracer) builds nothing.
TEST(TimedRender, TheSceneBuildIsTimedApart) {
  const Scene scene = cornell();
  RenderSettings s = timed("path", 0);
  s.spp = 1;
  RenderStats built;
  const RgbImage a = render(scene, s, built);
  EXPECT_GT(built.buildSeconds, 0.0);
  s.tracer = buildTracer(scene, 1);
  RenderStats reused;
  const RgbImage b = render(scene, s, reused);
  EXPECT_EQ(reused.buildSeconds, 0.0);
  test::expectBitIdentical(a, b);
}

}  // namespace
}  // namespace erpt
