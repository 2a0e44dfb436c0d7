// `erpt diff` (numbers and heat map), `erpt compare` (table, JSON, plot) and `erpt info` from
// the command line.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "io/error_heatmap.h"
#include "erpt/image_io.h"
#include "support/test_support.h"

namespace erpt {
namespace {

std::string cornell() { return test::sharedScenesDir() + "/cornell-box/scene.xml"; }

// `erpt info` names every shape, light and material kind the loader made, exact spheres and
// tessellated ones included.
TEST(InfoCli, ListsShapesLightsAndMaterials) {
  test::TempDir dir;
  const std::string scene = dir.write("s.xml", R"(<scene version="3.0.0">
    <shape type="sphere" id="ball"><float name="radius" value="0.5"/>
      <bsdf type="roughdielectric"><float name="alpha" value="0.2"/></bsdf></shape>
    <shape type="cylinder"><bsdf type="phong"/></shape>
    <emitter type="spot"><rgb name="intensity" value="5"/></emitter>
    <emitter type="directional"><rgb name="irradiance" value="2"/></emitter>
  </scene>)");
  const test::CommandResult r = test::runCli("info " + scene);
  EXPECT_EQ(r.exitCode, 0) << r.output;
  for (const char* line : {"spheres:    1 (exact)", "sphere 'ball': exact sphere, radius 0.5", "cylinder: 2048 triangles",
                           "  spot (5, 5, 5)", "  directional (2, 2, 2)", "roughdielectric", "phong"})
    EXPECT_NE(r.output.find(line), std::string::npos) << line << "\n" << r.output;
  const test::CommandResult t = test::runCli("info --tessellate-spheres " + scene);
  EXPECT_NE(t.output.find("spheres:    0 (exact)"), std::string::npos) << t.output;
  EXPECT_NE(t.output.find("sphere 'ball': 261120 triangles"), std::string::npos) << t.output;
}

RgbImage row(std::initializer_list<Color> pixels) {
  RgbImage img;
  img.width = int(pixels.size());
  img.height = 1;
  img.pixels = pixels;
  return img;
}

// The numbers after `key` on its line of the diff output.
std::vector<double> valuesOf(const std::string& output, const std::string& key) {
  std::istringstream in(output);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(key + " ", 0) != 0) continue;
    std::istringstream fields(line.substr(key.size()));
    std::vector<double> out;
    for (double v; fields >> v;) out.push_back(v);
    return out;
  }
  return {};
}

// Black pixels: exactly (0, 0, 0), counted alone and where the reference has light.
TEST(DiffCli, CountsBlackPixels) {
  test::TempDir dir;
  writeImageAtomic(dir.file("a.exr"), row({Color(0.0f), Color(0.2f), Color(0.0f), Color(0, 0, 1e-30f)}));
  writeImageAtomic(dir.file("r.exr"), row({Color(0.0f), Color(0.2f), Color(0.1f), Color(0.1f)}));
  const test::CommandResult r = test::runCli("diff " + dir.file("a.exr") + " " + dir.file("r.exr"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("black_pixels 2 (50.00%), 1 where the reference is not black (25.00%)"), std::string::npos)
      << r.output;
}

// Hand-computed: image (1, .5, 0), (.2, .2, .2), (NaN, 0, 0) against reference (.5, .5, .1),
// (.2, .1, .3), (.35, .3, .2). The NaN pixel is counted and left out; squared differences
// .25, 0, .01, 0, .01, .01 give MSE .28 / 6; relative ones .25/.26 + .01/.02 + .01/.02 + .01/.1
// give relMSE 2.0615385 / 6. Means (.6, .35, .1) against (.35, .3, .2).
TEST(DiffCli, KnownImagesGiveKnownNumbers) {
  test::TempDir dir;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  writeImageAtomic(dir.file("a.exr"), row({Color(1, 0.5f, 0), Color(0.2f), Color(nan, 0, 0)}));
  writeImageAtomic(dir.file("r.exr"), row({Color(0.5f, 0.5f, 0.1f), Color(0.2f, 0.1f, 0.3f), Color(0.35f, 0.3f, 0.2f)}));
  const test::CommandResult r = test::runCli("diff " + dir.file("a.exr") + " " + dir.file("r.exr") + " --heatmap " + dir.file("h.png"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  auto expectValues = [&](const std::string& key, std::vector<double> expected) {
    const std::vector<double> got = valuesOf(r.output, key);
    ASSERT_EQ(got.size(), expected.size()) << key << "\n" << r.output;
    for (size_t i = 0; i < got.size(); ++i) EXPECT_NEAR(got[i], expected[i], 1e-5 * std::max(1.0, expected[i])) << key << " " << i;
  };
  expectValues("mse", {0.28 / 6});
  expectValues("relmse", {(0.25 / 0.26 + 0.5 + 0.5 + 0.1) / 6});
  expectValues("mean", {0.6, 0.35, 0.1});
  expectValues("reference_mean", {0.35, 0.3, 0.2});
  expectValues("mean_ratio", {0.6 / 0.35, 0.35 / 0.3, 0.5});
  expectValues("nonfinite_pixels", {1});
  // The heat map: magnified to 256 pixels wide (x86), a colour bar below; pixel 1's error
  // (0 + .5 + .1) / 3 = .2 on the log scale 1e-5..1, the NaN pixel cyan.
  const RgbImage heat = readImage(dir.file("h.png"));
  ASSERT_EQ(heat.width, 258);
  EXPECT_GT(heat.height, 86);
  const Rgb8 expected = heatColor((std::log10(0.2) + 5) / 5);
  const Color got = heat.at(86 + 43, 40);
  EXPECT_NEAR(got.x * 255, expected.r, 1.0);
  EXPECT_NEAR(got.y * 255, expected.g, 1.0);
  EXPECT_NEAR(got.z * 255, expected.b, 1.0);
  const Color cyan = heat.at(2 * 86 + 43, 40);
  EXPECT_EQ(cyan.x, 0.0f);
  EXPECT_EQ(cyan.y, 1.0f);
}

// A reference of another size: an integer multiple is box-averaged, and the output says so
// (a line of its own, so the figures are never read as against the full-size reference);
// other sizes are refused. The same size prints no such line.
TEST(DiffCli, SaysWhenTheReferenceWasDownsampled) {
  test::TempDir dir;
  writeImageAtomic(dir.file("a.exr"), row({Color(1.0f), Color(2.0f)}));
  RgbImage big;
  big.width = 4, big.height = 2;
  big.pixels = {Color(0.5f), Color(1.5f), Color(2.0f), Color(2.0f), Color(1.0f), Color(1.0f), Color(2.0f), Color(2.0f)};
  writeImageAtomic(dir.file("big.exr"), big);
  test::CommandResult r = test::runCli("diff " + dir.file("a.exr") + " " + dir.file("big.exr"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("reference_downsampled 2 (the reference (4x2) is box-averaged over 2x2 pixels to the image's 2x1"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("mse 0\n"), std::string::npos) << r.output;  // (0.5 + 1.5 + 1 + 1) / 4 = 1, then 2
  r = test::runCli("diff " + dir.file("a.exr") + " " + dir.file("a.exr"));
  EXPECT_EQ(r.output.find("reference_downsampled"), std::string::npos) << r.output;
  writeImageAtomic(dir.file("odd.exr"), row({Color(1.0f), Color(1.0f), Color(1.0f)}));
  r = test::runCli("diff " + dir.file("a.exr") + " " + dir.file("odd.exr"));
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.output.find("not the same size or an integer multiple"), std::string::npos) << r.output;
}

TEST(DiffCli, UnreadableFilesAndBadHeatmapNamesAreClearErrors) {
  test::TempDir dir;
  writeImageAtomic(dir.file("a.exr"), row({Color(1.0f)}));
  const std::string garbage = dir.write("garbage.exr", "this is not an image");
  test::CommandResult r = test::runCli("diff " + dir.file("a.exr") + " " + garbage);
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.output.find("garbage.exr"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("cannot read image"), std::string::npos) << r.output;
  r = test::runCli("diff " + dir.file("a.exr") + " " + dir.file("a.exr") + " --heatmap " + dir.file("h.tiff"));
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.output.find("--heatmap must name a .png"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir.file("h.tiff")));
}

size_t countOf(const std::string& s, const std::string& what) {
  size_t n = 0;
  for (size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}

// A short comparison on a tiny image: a Markdown row per integrator on stdout, the same table
// and the command in compare.md, a JSON report with an error curve per integrator, the plot,
// and each integrator's image and heat map.
TEST(CompareCli, ShortRunGivesOneRowPerIntegratorAndAPlot) {
  test::TempDir dir;
  const std::string ref = dir.file("ref.exr");
  ASSERT_EQ(test::runCli("render -q " + cornell() + " --width 16 --height 16 --spp 64 -o " + ref).exitCode, 0);
  const std::string out = dir.file("cmp");
  const test::CommandResult r = test::runCli("compare -q " + cornell() + " --width 16 --height 16 --spp 4 --reference " + ref +
                                             " --time 0.4 --integrators 'path,erpt,erpt[--pm-filter --max-consecutive 5]' --out " + out);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("| integrator | time (s) | spp | mutations | MSE | relMSE |"), std::string::npos) << r.output;
  for (const char* name : {"| path |", "| erpt |", "| erpt[--pm-filter --max-consecutive 5] |"})
    EXPECT_EQ(countOf(r.output, name), 1u) << name << r.output;
  std::ifstream json(out + "/compare.json");
  std::stringstream js;
  js << json.rdbuf();
  EXPECT_EQ(countOf(js.str(), "\"integrator\":"), 3u) << js.str();
  EXPECT_EQ(countOf(js.str(), "\"curve\":"), 3u);
  std::ifstream md(out + "/compare.md");
  std::stringstream mds;
  mds << md.rdbuf();
  EXPECT_NE(mds.str().find("erpt compare"), std::string::npos);
  // The plot is drawn by the Python package (python/erpt/plot.py) when it was built beside the
  // binary (the Release build); without it (the sanitizer builds) compare says how to draw it.
  if (std::filesystem::exists(std::filesystem::path(ERPT_CLI_PATH).parent_path() / "python" / "erpt" / "plot.py")) {
    EXPECT_EQ(r.output.find("no compare.png"), std::string::npos) << r.output;
    const RgbImage plot = readImage(out + "/compare.png");
    EXPECT_GT(plot.width, 500);
  } else {
    EXPECT_NE(r.output.find("no compare.png: "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("-m erpt.plot " + out + "/compare.json -o " + out + "/compare.png"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(out + "/compare.png"));
  }
  // --json prints the report itself (what compare.json holds) instead of the table.
  const test::CommandResult j = test::runCli("compare -q " + cornell() + " --width 8 --height 8 --spp 1 --reference " + ref +
                                             " --time 0.05 --integrators direct --json --out " + dir.file("cmp2"));
  ASSERT_EQ(j.exitCode, 0) << j.output;
  EXPECT_NE(j.output.find("\"results\": ["), std::string::npos) << j.output;
  EXPECT_EQ(j.output.find("| integrator |"), std::string::npos) << j.output;
  for (const char* name : {"path", "erpt", "erpt---pm-filter---max-consecutive-5"}) {
    EXPECT_TRUE(std::filesystem::exists(out + "/" + name + ".exr")) << name;
    EXPECT_TRUE(std::filesystem::exists(out + "/" + name + "-error.png")) << name;
  }
}

// Mistakes are reported before anything renders, and nothing is written.
TEST(CompareCli, BadArgumentsFailBeforeRendering) {
  test::TempDir dir;
  writeImageAtomic(dir.file("ref24.exr"), RgbImage{24, 24, std::vector<Color>(24 * 24, Color(0.5f)), {}});
  const std::string base = "compare -q " + cornell() + " --width 16 --height 16 --time 0.2 --out " + dir.file("o");
  struct Case {
    std::string args, message;
  };
  for (const Case& c : {Case{" --reference " + dir.file("ref24.exr"), "not the same size"},
                        Case{" --reference " + dir.file("missing.exr"), "missing.exr"},
                        Case{" --reference " + dir.file("ref24.exr") + " --integrators path,vcm", "unknown integrator 'vcm'"},
                        Case{" --reference " + dir.file("ref24.exr") + " --integrators 'erpt[--flow sideways]'", "--flow"},
                        Case{" --reference " + dir.file("ref24.exr") + " --integrators 'erpt[--spp 2'", "unbalanced"}}) {
    const test::CommandResult r = test::runCli(base + c.args);
    EXPECT_NE(r.exitCode, 0) << c.args;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << c.args << "\n" << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir.file("o"))) << c.args;
  }
}

}  // namespace
}  // namespace erpt
