// PMC-ER's population is bounded by what the render can use: at most one member per position
// of its stratified pool, and refused up front when the members would not fit in memory
// (--population 1e6 on an 8x8 image at 1 spp once took 3.3 GB and over two minutes; 1e7 ended
// in std::bad_alloc).
#include <gtest/gtest.h>

#include "erpt/error.h"
#include "erpt/render.h"
#include "erpt/scene_loader.h"
#include "integrators/pmc_er/pmc_er_integrator.h"
#include "support/test_support.h"

namespace erpt {
namespace {

RenderSettings pmcAt(int width, int height, int spp, int population) {
  RenderSettings s;
  s.integrator = "pmc-er";
  s.width = width;
  s.height = height;
  s.spp = spp;
  pmcOf(s).population = population;
  return s;
}

TEST(PmcPopulationBound, AtMostOneMemberPerPoolPosition) {
  EXPECT_EQ(usablePopulation(pmcAt(8, 8, 1, 10000000), 0), 64);
  EXPECT_EQ(usablePopulation(pmcAt(7, 5, 3, 10000000), 0), 105);  // not a power of two
  EXPECT_EQ(usablePopulation(pmcAt(128, 128, 4, 5000), 0), 5000);
}

TEST(PmcPopulationBound, RefusesWhatWouldNotFitBeforeAllocating) {
  const RenderSettings big = pmcAt(4000, 4000, 1, 10000000);
  const size_t oneGigabyte = size_t(1) << 30;
  try {
    usablePopulation(big, oneGigabyte);
    FAIL() << "ten million members fit in 1 GB?";
  } catch (const UsageError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("--population 10000000 needs about"), std::string::npos) << message;
    EXPECT_NE(message.find("available"), std::string::npos) << message;
  }
  // The same members with room for them: accepted.
  EXPECT_EQ(usablePopulation(big, size_t(1) << 50), 10000000);
}

// The case end to end: ten million members asked for on an 8x8 image at 1 spp render
// with the pool's 64, quickly, and the statistics say so.
TEST(PmcPopulationBound, HugePopulationOnATinyImageRendersWithThePool) {
  Scene scene = loadScene(test::sourceDir() + "/scenes/default/scene.xml");
  RenderSettings s = pmcAt(8, 8, 1, 10000000);
  chainOf(s).directSamples = 2;
  erptOf(s).pilotSpp = 1;
  RenderStats stats;
  const RgbImage image = render(scene, resolveSettings(scene, s), stats);
  EXPECT_EQ(pmcStatsOf(stats).population, 64u);
  EXPECT_EQ(pmcStatsOf(stats).requestedPopulation, 10000000u);
  EXPECT_EQ(image.width, 8);
}

}  // namespace
}  // namespace erpt
