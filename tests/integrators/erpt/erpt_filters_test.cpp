// The noise filters of the paper's section 4.4 (proposed mutations, consecutive samples) and
// the detailed balance flow rule of section 3.1.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "integrators/chain_lanes.h"
#include "integrators/noise_filters.h"
#include "erpt/render.h"
#include "core/rng.h"
#include "erpt/scene_loader.h"
#include "support/erpt_world.h"
#include "support/image_stats.h"
#include "support/test_support.h"

namespace erpt {
namespace {

using test::ChainQueues;
using test::ErptWorld;

RgbImage imageOf(int w, int h, Color c) {
  RgbImage img;
  img.width = w;
  img.height = h;
  img.pixels.assign(size_t(w) * h, c);
  return img;
}

// A constant tally means every pixel got its expected share of proposals: nothing changes,
// the border included (the window is cut to the image there).
TEST(NoiseFilters, ProposalFilterLeavesAnImageWithConstantTallyUnchanged) {
  RgbImage img = imageOf(9, 7, Color(0.25f, 0.5f, 2.0f));
  img.pixels[10] = Color(3, 1, 0);  // not constant: the filter must not blur the image itself
  const std::vector<uint32_t> tally(size_t(9) * 7, 17);
  for (int radius : {0, 1, 3, 20}) {
    const RgbImage out = applyProposalFilter(img, tally, radius);
    for (size_t i = 0; i < img.pixels.size(); ++i)
      for (int c = 0; c < 3; ++c) EXPECT_EQ(out.pixels[i][c], img.pixels[i][c]) << "radius " << radius << " pixel " << i;
  }
}

// Known numbers: a 3x3 tally of 10s with 20 in the middle, radius 1. The middle pixel's window
// is the whole image: expected = (8 * 10 + 20) / 9; a corner's window is 2x2: (3 * 10 + 20) / 4;
// an edge's 2x3: (5 * 10 + 20) / 6. Pixels without proposals keep their value.
TEST(NoiseFilters, ProposalFilterScalesByExpectedOverActualProposals) {
  std::vector<uint32_t> tally(9, 10);
  tally[4] = 20;
  const std::vector<float> expected = expectedProposals(tally, 3, 3, 1);
  EXPECT_FLOAT_EQ(expected[4], 100.0f / 9);
  EXPECT_FLOAT_EQ(expected[0], 50.0f / 4);
  EXPECT_FLOAT_EQ(expected[1], 70.0f / 6);
  const RgbImage out = applyProposalFilter(imageOf(3, 3, Color(1.0f)), tally, 1);
  EXPECT_FLOAT_EQ(out.pixels[4].x, (100.0f / 9) / 20);
  EXPECT_FLOAT_EQ(out.pixels[0].y, (50.0f / 4) / 10);
  tally[8] = 0;
  EXPECT_EQ(applyProposalFilter(imageOf(3, 3, Color(0.5f)), tally, 1).pixels[8].z, 0.5f);
}

// Chains whose lens moves are tiny stay on one pixel for many steps. With the filter at N, no
// chain deposits more than N times in a row on one pixel; without it, longer runs happen (so
// the test can see the difference).
TEST(NoiseFilters, ConsecutiveSampleFilterCapsRunsOnOnePixel) {
  ErptWorld w(test::sharedScenesDir() + "/cornell-box/scene.xml", 32, 2, FilterKind::Box);
  constexpr uint32_t kMax = 5, kSteps = 40;
  auto longestRun = [&](uint32_t maxConsecutive, uint64_t* discarded) {
    ChainQueues q(1024);
    const size_t loaded = q.loadSeeds(w, kSteps, 1.0f, 5);
    StepConfig ctx = w.stepContext(MutationStrategy::LensOnly);
    ctx.settings.lensRadius = 0.4f;
    DepositFilters filters;
    filters.maxConsecutive = maxConsecutive;
    Film film(w.width, w.height);
    std::vector<uint32_t> lastPixel(loaded, kNoPixel), run(loaded, 0);
    uint32_t longest = 0;
    for (uint32_t step = 0; step < kSteps; ++step) {
      q.propose(w, ctx);
      StepCounters counters;
      stageChainAccept(ctx, q.chains, q.chainVertices, q.proposals, q.proposalVertices, q.deposits, counters,
                      IndexRange{0, q.chains.size()});
      for (size_t i = 0; i < loaded; ++i) {
        // The paper's rule: one record per step, at the chain's path after the step.
        const uint32_t pixel = uint32_t(std::floor(q.deposits.y[i * kDepositsPerStep])) * 1024u + uint32_t(std::floor(q.deposits.x[i * kDepositsPerStep]));
        const bool deposited = applyDeposits(q.chains, q.proposals, q.deposits, IndexRange{i, i + 1}, *w.density, film, filters) > 0;
        if (!deposited) {
          run[i] = 0;
          lastPixel[i] = kNoPixel;
          continue;
        }
        run[i] = pixel == lastPixel[i] ? run[i] + 1 : 1;
        lastPixel[i] = pixel;
        longest = std::max(longest, run[i]);
      }
    }
    *discarded = filters.discarded;
    return longest;
  };
  uint64_t discardedOff = 0, discardedOn = 0;
  EXPECT_GT(longestRun(0, &discardedOff), 3 * kMax);
  EXPECT_EQ(discardedOff, 0u);
  EXPECT_LE(longestRun(kMax, &discardedOn), kMax);
  EXPECT_GT(discardedOn, 1000u);
}

RenderSettings smallErpt(int size, int spp) {
  RenderSettings s;
  s.integrator = "erpt";
  s.width = s.height = size;
  s.spp = spp;
  s.seed = 3;
  chainOf(s).mutationsPerPixel = 20;
  erptOf(s).chainLength = 20;
  return s;
}

bool sameImage(const RgbImage& a, const RgbImage& b) {
  if (a.width != b.width || a.height != b.height) return false;
  for (size_t i = 0; i < a.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c)
      if (a.pixels[i][c] != b.pixels[i][c]) return false;
  return true;
}

// Both filters are off by default. Turning the proposed-mutations filter on leaves the chains
// alone: its "raw" image is bit for bit the unfiltered render, and the result differs from it.
// The consecutive-sample filter changes the image only when on.
TEST(NoiseFilters, OffByDefaultAndTheUnfilteredImageIsKept) {
  const ChainOptions defaults;
  EXPECT_EQ(defaults.pmFilterRadius, -1);
  EXPECT_EQ(defaults.maxConsecutive, 0);
  EXPECT_EQ(int(ErptSettings{}.flow), int(FlowRule::EqualDeposition));
  const Scene scene = loadScene(test::sharedScenesDir() + "/cornell-box/scene.xml");
  RenderStats plainStats, pmStats, consecutiveStats;
  const RenderSettings plain = smallErpt(32, 4);
  const RgbImage unfiltered = render(scene, plain, plainStats);
  EXPECT_TRUE(plainStats.extraImages.empty());
  EXPECT_EQ(chainStatsOf(plainStats).discardedDeposits, 0u);
  RenderSettings pm = plain;
  chainOf(pm).pmFilterRadius = 3;
  const RgbImage filtered = render(scene, pm, pmStats);
  auto extra = [&](const std::string& name) -> const RgbImage& {
    for (const auto& [n, img] : pmStats.extraImages)
      if (n == name) return img;
    ADD_FAILURE() << "no extra image " << name;
    return unfiltered;
  };
  ASSERT_EQ(pmStats.extraImages.size(), 3u);
  EXPECT_TRUE(sameImage(extra("raw"), unfiltered));
  EXPECT_FALSE(sameImage(filtered, unfiltered));
  EXPECT_TRUE(sameImage(filtered, proposalFilteredImage(extra("raw"), extra("chains"), extra("proposals"), 3)));
  double proposals = 0;
  for (const Color& c : extra("proposals").pixels) proposals += c.x;
  EXPECT_GT(proposals, 0.5 * double(chainStatsOf(pmStats).mutations));  // most proposals are complete paths
  EXPECT_LE(proposals, double(chainStatsOf(pmStats).mutations));
  RenderSettings consecutive = plain;
  chainOf(consecutive).maxConsecutive = 2;
  const RgbImage capped = render(scene, consecutive, consecutiveStats);
  EXPECT_GT(chainStatsOf(consecutiveStats).discardedDeposits, 0u);
  EXPECT_FALSE(sameImage(capped, unfiltered));
  EXPECT_TRUE(sameImage(render(scene, plain, plainStats), unfiltered));
}

// Detailed balance flow (section 3.1) at the stage level: the chain stays at x, the mutation
// receives e q / m and x keeps e (1 - q) / m.
TEST(DetailedBalanceFlow, MutationsReceiveTheAcceptedShareAndTheSeedKeepsTheRest) {
  ErptWorld w(test::sourceDir() + "/scenes/default/scene.xml", 32, 2, FilterKind::Box);
  ChainQueues q(1024);
  const size_t loaded = q.loadSeeds(w, 4, 0.25f, 6);
  StepConfig ctx = w.stepContext(MutationStrategy::Paper);
  ctx.settings.flow = FlowRule::DetailedBalance;
  q.propose(w, ctx);
  const ChainQueue before = q.chains;
  StepCounters counters;
  stageChainAccept(ctx, q.chains, q.chainVertices, q.proposals, q.proposalVertices, q.deposits, counters,
                  IndexRange{0, q.chains.size()});
  size_t flowed = 0;
  for (size_t i = 0; i < loaded; ++i) {
    const float qa = q.proposals.acceptance[i];
    flowed += qa > 0;
    EXPECT_EQ(q.chains.filmX[i], before.filmX[i]);
    EXPECT_EQ(q.chains.filmY[i], before.filmY[i]);
    EXPECT_EQ(q.deposits.x[i * kDepositsPerStep], before.filmX[i]);
    EXPECT_NEAR(luminance(q.deposits.energyAt(i * kDepositsPerStep + 0)), 0.25f * (1 - qa), 1e-5);
    EXPECT_NEAR(luminance(q.deposits.energyAt(i * kDepositsPerStep + 1)), 0.25f * qa, 1e-5);
    if (qa > 0) {
      EXPECT_EQ(q.deposits.x[i * kDepositsPerStep + 1], q.proposals.filmX[i]);
    }
  }
  EXPECT_GT(flowed, loaded / 3);
}

// The detailed balance rule is unbiased: ERPT with it (chains on every path, direct light
// included, 8 mutations per seed) matches the channel means of Tungsten's Cornell box render
// within 1%. Dropping the share that stays at x, or giving mutations e / m instead of e q / m,
// moves the means by far more.
TEST(StatisticalErpt, DetailedBalanceFlowIsUnbiased) {
  const std::string dir = test::sharedScenesDir() + "/cornell-box";
  const Scene scene = loadScene(dir + "/scene.xml");
  const RgbImage tungsten = readImage(dir + "/TungstenRender.exr");
  RenderSettings s = smallErpt(128, 16);
  s.filterSet = true;
  s.filter = FilterKind::Box;
  erptOf(s).flow = FlowRule::DetailedBalance;
  erptOf(s).chainLength = 8;
  chainOf(s).directSamples = -1;
  RenderStats stats;
  const RgbImage img = render(scene, s, stats);
  EXPECT_EQ(stats.invalidSamples, 0u);
  uint64_t inPlace = 0;
  for (uint64_t n : chainStatsOf(stats).inPlace) inPlace += n;
  EXPECT_EQ(chainStatsOf(stats).chains + inPlace, chainStatsOf(stats).seeds);  // one per seed, but those deposited in place
  const Color m = test::meanOf(img), r = test::meanOf(tungsten);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(m[c] / r[c], 1.0, 0.01) << "channel " << c;
  std::printf("means %.4f %.4f %.4f vs %.4f %.4f %.4f, relMSE vs 128 reference %.3g\n", m.x, m.y, m.z, r.x, r.y, r.z,
              test::relativeMse(img, readImage(dir + "/reference-box-128.exr")));
}

}  // namespace
}  // namespace erpt
