// `erpt render --integrator pmc-er` from the command line: the image, the strategy image and
// the summary; options shared with ERPT (filters, --time) work.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "erpt/image_io.h"
#include "support/test_support.h"

namespace erpt {
namespace {

std::string defaultScene() { return test::sourceDir() + "/scenes/default/scene.xml"; }

TEST(PmcCli, RendersTheImageTheStrategyImageAndTheSummary) {
  test::TempDir dir;
  const std::string out = dir.file("p.exr");
  for (const char* flow : {"equal-deposition", "balance"}) {
    test::CommandResult r = test::runCli("render -q " + defaultScene() + " --integrator pmc-er --pmc-flow " + flow +
                                         " --width 32 --height 32 --spp 2 --population 300 -o " + out);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(std::filesystem::exists(out));
    ASSERT_TRUE(std::filesystem::exists(dir.file("p-strategy.exr")));
    const RgbImage strategy = readImage(dir.file("p-strategy.exr"));
    ASSERT_EQ(strategy.width, 32);
    double deposits = 0, maxRadius = 0;
    for (const Color& c : strategy.pixels) deposits += c.x, maxRadius = std::max(maxRadius, double(c.y));
    EXPECT_GT(deposits, 1000);
    EXPECT_LE(maxRadius, 10.0 + 1e-3);  // mean radius chosen: within the mixture's radii (2, 5, 10)
    for (const char* s : {"iterations", "population 300", "pool 2048 of 2048 positions", "radius 2:", "radius 10:",
                          "alpha histogram", "energy regenerated", "eliminated", "resampling", "regeneration"})
      EXPECT_NE(r.output.find(s), std::string::npos) << s << "\n" << r.output;
  }
}

TEST(PmcCli, FiltersAndTimeBudgetsWork) {
  test::TempDir dir;
  const std::string out = dir.file("p.exr");
  test::CommandResult r = test::runCli("render -q " + defaultScene() +
                                       " --integrator pmc-er --width 24 --height 24 --spp 1 --population 200 "
                                       "--pm-filter --max-consecutive 10 -o " + out);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const char* f : {"p.exr", "p-raw.exr", "p-chains.exr", "p-proposals.exr", "p-strategy.exr"})
    EXPECT_TRUE(std::filesystem::exists(dir.file(f))) << f;
  // Under --time one population takes whole rounds of the pool (every pixel the same number
  // of samples) while the next fits: the pool taken is a multiple of the 24 x 24 pixels.
  r = test::runCli("render -q " + defaultScene() + " --integrator pmc-er --width 24 --height 24 --population 200 --time 1 -o " + out);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  unsigned long long taken = 0, size = 0;
  const size_t at = r.output.find("pool ");
  ASSERT_NE(at, std::string::npos) << r.output;
  ASSERT_EQ(std::sscanf(r.output.c_str() + at, "pool %llu of %llu", &taken, &size), 2) << r.output;
  EXPECT_EQ(taken, size);
  EXPECT_GT(taken, 0u);
  EXPECT_EQ(taken % 576, 0u) << r.output;
  EXPECT_TRUE(std::filesystem::exists(dir.file("p-strategy.exr")));
}

}  // namespace
}  // namespace erpt
