// PMC-ER under --time (pmc_time_budget.cpp, docs/pmc-er.md "Time budgets"): one population
// over an open-ended pool, stopped by the clock at a round boundary.
//  - The stop rule adds nothing of its own: a population told by `allowed` to stop after R
//    rounds of the open-ended pool leaves the film a fixed run over R rounds leaves, bit for
//    bit, so the time-budgeted image is a fixed-spp image at the R the clock chose.
//  - A budget shorter than one round still takes round 0 whole; whole --time renders are
//    unbiased block by block.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdio>
#include <memory>
#include <vector>

#include "erpt/render.h"
#include "erpt/scene_loader.h"
#include "integrators/pmc_er/pmc_er_integrator.h"
#include "integrators/pmc_er/pmc_population.h"
#include "integrators/pmc_er/stratified_pool.h"
#include "integrators/render_setup.h"
#include "support/block_bias.h"
#include "support/test_support.h"

namespace erpt {
namespace {

Scene defaultScene() { return loadScene(test::sourceDir() + "/scenes/default/scene.xml"); }

RenderSettings pmcSettings(int width, int height, int spp, int population) {
  RenderSettings s;
  s.integrator = "pmc-er";
  s.width = width;
  s.height = height;
  s.spp = spp;
  s.seed = 17;
  pmcOf(s).population = population;
  pmcOf(s).adapt = PmcAdapt::Off;
  chainOf(s).directSamples = -1;
  return s;
}

// The film after one population run over `rounds` with `allowed` (unset: all of them).
std::vector<float> populationFilm(const Scene& scene, const RenderSettings& s, const PoolRounds& rounds,
                                  const std::function<size_t(size_t)>& allowed) {
  RenderSetup setup(scene, s);
  FilmDensity density(setup.filter, s.width, s.height);
  const StepConfig ctx{MeasureContext{scene, setup.lights, setup.camera, density}, pmcStepSettings(s)};
  PmcMixture mixture(pmcOf(s), s.width, s.height);
  RenderStats stats;
  PmcPopulation population(setup, PmcPopulation::Config{ctx, chainSettingsOf(chainOf(s)), pmcOf(s), s.seed, &setup.film},
                           mixture, stats);
  EXPECT_TRUE(population.run(rounds, -1, {}, nullptr, allowed));
  const RgbImage image = setup.film.resolve(1.0);
  std::vector<float> values;
  for (const Color& c : image.pixels) values.insert(values.end(), {c.x, c.y, c.z});
  return values;
}

TEST(PmcTimeBudget, StoppingAfterRoundsEqualsAFixedRunOfThoseRounds) {
  const Scene scene = defaultScene();
  // 23 x 17 pixels (not a power of two, not a multiple of the positions per iteration), three
  // lanes of members.
  const RenderSettings s = pmcSettings(23, 17, 4, 1100);
  const uint32_t pixels = 23 * 17, rounds = 3;
  const uint64_t poolSeed = 99;
  const std::vector<float> fixed =
      populationFilm(scene, s, PoolRounds::all(StratifiedPool{pixels, rounds, poolSeed}), {});
  size_t asked = 0;
  const std::vector<float> budgeted = populationFilm(
      scene, s, PoolRounds::all(StratifiedPool{pixels, 1u << 24, poolSeed}), [&](size_t taken) {
        ++asked;
        EXPECT_LE(taken, size_t(rounds) * pixels);
        return size_t(rounds) * pixels;
      });
  EXPECT_GT(asked, 3u);
  ASSERT_EQ(fixed.size(), budgeted.size());
  double total = 0;
  for (size_t i = 0; i < fixed.size(); ++i) {
    ASSERT_EQ(fixed[i], budgeted[i]) << "value " << i;
    total += fixed[i];
  }
  EXPECT_GT(total, 0.0);
}

// A budget shorter than one round of the pool: round 0 is finished all the same.
TEST(PmcTimeBudget, ABudgetShorterThanOneRoundStillTakesRoundZero) {
  RenderSettings s = pmcSettings(64, 64, 4, 600);
  s.timeBudget = 0.001;
  const Scene scene = defaultScene();
  RenderStats stats;
  render(scene, resolveSettings(scene, s), stats);
  EXPECT_EQ(pmcStatsOf(stats).poolUsed, 64u * 64u);
  EXPECT_EQ(stats.spp, 1);
}

// Whole --time renders, with the direct pass in chunks (at the ratio --direct-samples / --spp
// to the rounds taken), block by block. Every round count is unbiased, but a render of one or
// two rounds is so noisy that the z-test's tails grow (a sanitizer build got worst |z| 4.9 and
// 6.7 from renders the machine's clock cut short), so the budget reads a counting clock (each
// reading a millisecond later): the rounds taken, and the test's images, are the same on every
// machine and in every build.
TEST(StatisticalPmcTimeBudget, WholeRoundsAndTheSplitDirectPassAreUnbiasedBlockByBlock) {
  RenderSettings s = pmcSettings(0, 0, 2, 600);
  chainOf(s).directSamples = 4;
  s.timeBudget = 1.5;
  auto readings = std::make_shared<std::atomic<uint64_t>>(0);
  s.budgetClock = [readings] { return 5e-3 * double(readings->fetch_add(1)); };
  std::vector<int> rounds;
  test::BlockTestOptions options;
  options.beforeEachRun = [&] { *readings = 0; };
  options.afterEachRun = [&](const RenderStats& stats) { rounds.push_back(stats.spp); };
  test::expectMatchesPathTracerBlockByBlock(defaultScene(), s, 16, 7200, options);
  std::printf("rounds per render: %d\n", rounds.empty() ? 0 : rounds[0]);
  ASSERT_EQ(rounds.size(), 16u);
  for (int r : rounds) EXPECT_GE(r, 8) << "too few rounds for the z-test's tails";
}

}  // namespace
}  // namespace erpt
