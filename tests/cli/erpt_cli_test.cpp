// `erpt render --integrator erpt` and `erpt diff` from the command line.
#include <gtest/gtest.h>

#include <filesystem>

#include "support/test_support.h"

namespace erpt {
namespace {

std::string defaultScene() { return test::sourceDir() + "/scenes/default/scene.xml"; }

TEST(ErptCli, RendersAndPrintsTheChainSummary) {
  test::TempDir dir;
  const std::string out = dir.file("e.exr");
  test::CommandResult r = test::runCli("render -q " + defaultScene() + " --integrator erpt --width 32 --height 32 --spp 2 " +
                                       "--mutations-per-pixel 10 --chain-length 10 --mutation-strategy mixed -o " + out);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(out));
  for (const char* s : {"seeds", "chains", "mutations", "lens", "caustic", "accepted", "rejected:", "occluded",
                        "seeds deposited in place", "Mrays/s", "stage seconds: accept", " mutate ", " deposit "})
    EXPECT_NE(r.output.find(s), std::string::npos) << s << "\n" << r.output;
}

TEST(ErptCli, AbsurdOptionsAreRejectedBeforeRendering) {
  test::TempDir dir;
  const std::string out = dir.file("e.exr");
  for (const std::string args : {"--direct-samples 0", "--chain-length 0", "--mutation-strategy sideways",
                                 "--mutations-per-pixel -3", "--deposit maybe", "--lens-radius 0",
                                 "--pm-filter-radius -2", "--max-consecutive -1", "--flow sideways", "--time 0",
                                 "--flow detailed-balance --max-consecutive 5"}) {
    test::CommandResult r = test::runCli("render -q " + defaultScene() + " --integrator erpt " + args + " -o " + out);
    EXPECT_NE(r.exitCode, 0) << args;
    EXPECT_FALSE(r.output.empty()) << args;
    EXPECT_FALSE(std::filesystem::exists(out)) << args;
  }
}

// The proposed-mutations filter writes the raw image, the chains' part and the tally beside
// the filtered one; --time renders in passes and says how many.
TEST(ErptCli, FiltersKeepTheRawImageAndTimeBudgetsRenderInPasses) {
  test::TempDir dir;
  const std::string out = dir.file("e.exr");
  test::CommandResult r = test::runCli("render -q " + defaultScene() + " --integrator erpt --width 16 --height 16 --spp 2 " +
                                       "--mutations-per-pixel 5 --chain-length 10 --pm-filter --max-consecutive 10 --time 1 -o " + out);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const char* name : {"e.exr", "e.png", "e-raw.exr", "e-raw.png", "e-chains.exr", "e-proposals.exr"})
    EXPECT_TRUE(std::filesystem::exists(dir.file(name))) << name;
  EXPECT_NE(r.output.find(" spp"), std::string::npos) << r.output;
}

TEST(ErptCli, DiffReportsErrorsAndRejectsMismatchedSizes) {
  test::TempDir dir;
  const std::string a = dir.file("a.exr"), b = dir.file("b.exr");
  ASSERT_EQ(test::runCli("render -q " + defaultScene() + " --width 16 --height 16 --spp 1 -o " + a).exitCode, 0);
  ASSERT_EQ(test::runCli("render -q " + defaultScene() + " --width 16 --height 16 --spp 1 -o " + b).exitCode, 0);
  test::CommandResult same = test::runCli("diff " + a + " " + a);
  ASSERT_EQ(same.exitCode, 0) << same.output;
  EXPECT_NE(same.output.find("mse 0\n"), std::string::npos) << same.output;
  EXPECT_NE(same.output.find("mean_ratio 1.000000 1.000000 1.000000"), std::string::npos) << same.output;
  const std::string c = dir.file("c.exr");
  ASSERT_EQ(test::runCli("render -q " + defaultScene() + " --width 24 --height 16 --spp 1 -o " + c).exitCode, 0);
  test::CommandResult mismatch = test::runCli("diff " + a + " " + c);
  EXPECT_NE(mismatch.exitCode, 0);
  EXPECT_NE(mismatch.output.find("not the same size"), std::string::npos) << mismatch.output;
  test::CommandResult missing = test::runCli("diff " + a + " " + dir.file("nope.exr"));
  EXPECT_NE(missing.exitCode, 0);
  EXPECT_NE(missing.output.find("nope.exr"), std::string::npos) << missing.output;
}

}  // namespace
}  // namespace erpt
