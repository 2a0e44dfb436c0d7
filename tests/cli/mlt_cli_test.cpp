// `erpt render --integrator mlt` from the command line: the image and the summary, time
// budgets and `erpt compare`, and clear errors for options MLT does not take.
#include <gtest/gtest.h>

#include <filesystem>

#include "erpt/image_io.h"
#include "support/test_support.h"

namespace erpt {
namespace {

std::string defaultScene() { return test::sourceDir() + "/scenes/default/scene.xml"; }

TEST(MltCli, RendersTheImageAndTheSummary) {
  test::TempDir dir;
  const std::string out = dir.file("m.exr");
  test::CommandResult r = test::runCli("render -q " + defaultScene() +
                                       " --integrator mlt --width 32 --height 32 --mutations-per-pixel 16 "
                                       "--bootstrap 2 --chains 500 --large-step-prob 0.5 --direct-samples 2 -o " + out);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const RgbImage img = readImage(out);
  ASSERT_EQ(img.width, 32);
  for (const char* s : {"mlt: b ", "bootstrap: 2048 samples", "500 chains x 33 steps", "large step ", "lens ",
                        "accepted", "large step made no such path", "stage seconds: accept", " large step "})
    EXPECT_NE(r.output.find(s), std::string::npos) << s << "\n" << r.output;
}

TEST(MltCli, TimeBudgetsAndCompareWork) {
  test::TempDir dir;
  test::CommandResult r = test::runCli("render -q " + defaultScene() +
                                       " --integrator mlt --width 24 --height 24 --bootstrap 1 --direct-samples 1 "
                                       "--spp 4 --time 1 -o " + dir.file("t.exr"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("passes"), std::string::npos) << r.output;
  r = test::runCli("compare " + defaultScene() + " --reference " + test::sourceDir() +
                   "/tests/data/default-scene-path-64.exr --width 64 --height 64 --filter tent --time 1 "
                   "--integrators 'path,mlt[--bootstrap 1 --direct-samples 1]' --out " + dir.file("c") + " -q");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(dir.file("c/compare.md")));
}

TEST(MltCli, RefusesOptionsItDoesNotTake) {
  test::TempDir dir;
  const std::string base = "render -q " + defaultScene() + " --integrator mlt --width 8 --height 8 -o " + dir.file("x.exr");
  struct Case {
    const char* options;
    const char* message;
  } cases[] = {
      {"--large-step-prob 1.5", "--large-step-prob"},
      {"--chains 0", "--chains"},
      {"--pm-filter", "--pm-filter does not apply to --integrator mlt"},
      {"--flow detailed-balance", "--flow"},
      {"--checkpoint " , "checkpoint"},
  };
  for (const Case& c : cases) {
    std::string options = c.options;
    if (options == "--checkpoint ") options += dir.file("x.ckpt");
    const test::CommandResult r = test::runCli(base + " " + options);
    EXPECT_NE(r.exitCode, 0) << c.options;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << c.options << "\n" << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir.file("x.exr"))) << c.options;
  }
}

}  // namespace
}  // namespace erpt
