#include "support/block_bias.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include "io/checkpoint.h"
#include "support/image_stats.h"
#include "support/test_support.h"

namespace erpt::test {

namespace {
constexpr int kReferenceRuns = 16, kBlock = 8;

RgbImage renderWith(const Scene& scene, const RenderSettings& s, const std::function<void(const RenderStats&)>& after = {}) {
  RenderStats stats;
  RgbImage img = render(scene, s, stats);
  EXPECT_EQ(stats.invalidSamples, 0u);
  if (after) after(stats);
  return img;
}

// The reference: 16 path-traced renders, of 128 spp by default. Its variance of the mean is
// then 2-34% of most tests' z denominators (printed by each test): fewer spp would cost real
// power where it is largest (halving them at 34% shrinks z by 14%), more would add little.
BlockStats renderReference(const Scene& scene, const RenderSettings& settings, uint64_t seed, int spp) {
  std::vector<RgbImage> pathImages;
  for (int k = 0; k < kReferenceRuns; ++k) {
    RenderSettings s = settings;
    s.integrator = "path";
    s.spp = spp;
    s.stop = nullptr;  // the reference renders run in full
    s.onPasses = nullptr;
    s.seed = seed + 1000 + uint64_t(k);
    pathImages.push_back(renderWith(scene, s));
  }
  return blockStats(pathImages, kBlock);
}

// What the reference depends on, as text: the scene (its file's bytes and geometry: the
// checkpoint fingerprint), the camera (tests change it in code) and the path tracer's settings.
std::string referenceKey(const Scene& scene, const RenderSettings& s, uint64_t seed, int spp) {
  std::ostringstream key;
  key.precision(9);
  key << std::hex << sceneFingerprint(scene) << std::dec << " camera";
  const CameraSettings& c = scene.camera;
  for (double v : c.toWorld.m) key << ' ' << v;
  key << ' ' << c.fovDegrees << ' ' << int(c.fovAxis) << ' ' << c.nearClip << ' ' << c.farClip << ' '
      << c.apertureRadius << ' ' << c.focusDistance;
  key << " size " << s.width << 'x' << s.height << " filter " << int(s.filter) << " film " << int(s.film)
      << " max-depth " << s.maxDepth << " runs " << kReferenceRuns << " spp " << spp << " seeds "
      << seed + 1000;
  return key.str();
}

// tests/data/block-references/Suite.Test.txt (a test's second comparison adds ".2").
std::string referenceFile() {
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = std::string(info->test_suite_name()) + "." + info->name();
  for (char& ch : name)
    if (ch == '/') ch = '_';
  static std::map<std::string, int> calls;
  const int call = ++calls[name];
  if (call > 1) name += "." + std::to_string(call);
  return sourceDir() + "/tests/data/block-references/" + name + ".txt";
}

void writeReference(const std::string& path, const std::string& key, const BlockStats& stats, int spp) {
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  std::ofstream out(path);
  out << "# Per-block statistics (mean luminance sum of each 8x8 block and its variance of the mean) of "
      << kReferenceRuns << " path-traced renders of " << spp << " spp, made by our path tracer.\n"
      << "# Remade by: ERPT_WRITE_BLOCK_REFERENCES=1 build/tests/erpt_tests --gtest_filter='"
      << std::filesystem::path(path).stem().string() << "'\n"
      << "key " << key << '\n';
  out.precision(17);
  for (size_t k = 0; k < stats.mean.size(); ++k) out << stats.mean[k] << ' ' << stats.varianceOfMean[k] << '\n';
  if (!out) ADD_FAILURE() << "could not write " << path;
}

// The stored statistics, or none when the file is missing or was made for another key.
bool readReference(const std::string& path, const std::string& key, BlockStats& stats) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line) && line.rfind('#', 0) == 0) {
  }
  if (line != "key " + key) return false;
  for (double m, v; in >> m >> v;) stats.mean.push_back(m), stats.varianceOfMean.push_back(v);
  return !stats.mean.empty();
}
}  // namespace

BlockBiasResult expectMatchesPathTracerBlockByBlock(const Scene& scene, RenderSettings settings, int runs, uint64_t seed,
                                                    const BlockTestOptions& options) {
  settings.width = settings.height = 64;
  settings.filterSet = true;
  settings.filter = FilterKind::Box;
  // The path-traced reference is stored (it was half of the suite's statistical time): made
  // again, and written, with ERPT_WRITE_BLOCK_REFERENCES set; a file that is missing or that
  // was made for another scene, camera or settings fails the test.
  const std::string file = referenceFile(), key = referenceKey(scene, settings, seed, options.referenceSpp);
  BlockStats reference;
  if (std::getenv("ERPT_WRITE_BLOCK_REFERENCES")) {
    reference = renderReference(scene, settings, seed, options.referenceSpp);
    writeReference(file, key, reference, options.referenceSpp);
  } else if (!readReference(file, key, reference)) {
    ADD_FAILURE() << file << ": no stored reference for this scene and these settings; make it with "
                  << "ERPT_WRITE_BLOCK_REFERENCES=1 (the file's header says how)";
    return {};
  }
  std::vector<RgbImage> images;
  for (int k = 0; k < runs; ++k) {
    RenderSettings s = settings;
    s.seed = seed + uint64_t(k);
    if (options.beforeEachRun) options.beforeEachRun();
    images.push_back(renderWith(scene, s, options.afterEachRun));
  }
  const BlockZScores z = blockZScores(blockStats(images, kBlock), reference);
  std::printf("%s: %zu blocks of 8x8: mean z^2 %.2f, worst |z| %.2f (the reference's share of the variance %.0f%%)\n",
              settings.integrator.c_str(), z.z.size(), z.meanSquare, z.worst, 100 * z.secondShare);
  // Every block the reference has light in is compared (a scene may leave some black).
  const size_t lit = size_t(std::count_if(reference.varianceOfMean.begin(), reference.varianceOfMean.end(),
                                          [](double v) { return v > 0; }));
  EXPECT_GE(lit, 32u);
  EXPECT_GE(z.z.size(), lit);
  if (options.assertBounds) {
    EXPECT_LT(z.meanSquare, 2.0);
    EXPECT_LT(z.worst, 4.5);
  }
  return BlockBiasResult{z.meanSquare, z.worst};
}

RgbImage renderImage(const Scene& scene, const RenderSettings& settings, RenderStats* out) {
  RenderStats stats;
  RgbImage img = render(scene, settings, stats);
  EXPECT_EQ(stats.invalidSamples, 0u);
  if (out) *out = stats;
  return img;
}

}  // namespace erpt::test
