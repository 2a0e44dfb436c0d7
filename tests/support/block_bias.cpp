#include "support/block_bias.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

#include "support/image_stats.h"

namespace erpt::test {

namespace {
constexpr int kReferenceRuns = 16, kReferenceSpp = 128;

RgbImage renderWith(const Scene& scene, const RenderSettings& s) {
  RenderStats stats;
  RgbImage img = render(scene, s, stats);
  EXPECT_EQ(stats.invalidSamples, 0u);
  return img;
}
}  // namespace

BlockBiasResult expectMatchesPathTracerBlockByBlock(const Scene& scene, RenderSettings settings, int runs, uint64_t seed,
                                                    bool assertBounds, const std::function<void()>& beforeEachRun) {
  settings.width = settings.height = 64;
  settings.filterSet = true;
  settings.filter = FilterKind::Box;
  std::vector<RgbImage> images, pathImages;
  for (int k = 0; k < runs; ++k) {
    RenderSettings s = settings;
    s.seed = seed + uint64_t(k);
    if (beforeEachRun) beforeEachRun();
    images.push_back(renderWith(scene, s));
  }
  // The reference: 16 renders of 128 spp. Its variance is a small part of the z-scores' (the
  // renders under test are far noisier than 2048 path samples per pixel), so more spp would
  // add little power: with half these (8 x 512 spp before) the denominator was ~5% smaller.
  for (int k = 0; k < kReferenceRuns; ++k) {
    RenderSettings s = settings;
    s.integrator = "path";
    s.spp = kReferenceSpp;
    s.stop = nullptr;  // the reference renders run in full
    s.onPasses = nullptr;
    s.seed = seed + 1000 + uint64_t(k);
    pathImages.push_back(renderWith(scene, s));
  }
  const BlockZScores z = blockZScores(images, pathImages, 8);
  std::printf("%s: %zu blocks of 8x8: mean z^2 %.2f, worst |z| %.2f\n", settings.integrator.c_str(), z.z.size(),
              z.meanSquare, z.worst);
  EXPECT_EQ(z.z.size(), 64u);
  if (assertBounds) {
    EXPECT_LT(z.meanSquare, 2.0);
    EXPECT_LT(z.worst, 4.5);
  }
  return BlockBiasResult{z.meanSquare, z.worst};
}

}  // namespace erpt::test
