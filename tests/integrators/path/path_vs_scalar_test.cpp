// The wavefront path tracer and the plain scalar one in tests/support agree: block averages
// of the two images differ by no more than their combined statistical error allows.
#include <gtest/gtest.h>

#include "erpt/render.h"
#include "erpt/scene_loader.h"
#include "support/image_stats.h"
#include "support/scalar_path_tracer.h"
#include "support/test_support.h"

namespace erpt {
namespace {

// Per-pixel variance of the wavefront image, from two independent renders (different
// seeds): Var(mean of a and b) = E[(a - b)^2] / 4 per pixel, averaged over a block.
void compareBlocks(const std::string& scenePath, int size, int spp, int scalarSpp, int block) {
  Scene scene = loadScene(scenePath);
  RenderSettings s;
  s.integrator = "path";
  s.width = s.height = size;
  s.spp = spp;
  s.filterSet = true;
  s.filter = FilterKind::Box;
  RenderStats stats;
  s.seed = 1;
  RgbImage a = render(scene, s, stats);
  s.seed = 2;
  RgbImage b = render(scene, s, stats);
  RgbImage scalarVar;
  RgbImage scalar = test::scalarPathTrace(scene, size, size, scalarSpp, scene.integrator.maxDepth, 99, &scalarVar);

  int blocksOff = 0, blocks = 0;
  double worstZ = 0;
  for (int by = 0; by < size; by += block)
    for (int bx = 0; bx < size; bx += block) {
      for (int c = 0; c < 3; ++c) {
        double wave = 0, sc = 0, varWave = 0, varScalar = 0;
        int n = 0;
        for (int y = by; y < by + block; ++y)
          for (int x = bx; x < bx + block; ++x) {
            double av = a.at(x, y)[c], bv = b.at(x, y)[c];
            wave += 0.5 * (av + bv);
            varWave += (av - bv) * (av - bv) / 4.0;
            sc += scalar.at(x, y)[c];
            varScalar += scalarVar.at(x, y)[c];
            ++n;
          }
        double diff = (wave - sc) / n, sigma = std::sqrt(varWave + varScalar) / n;
        double z = sigma > 0 ? std::abs(diff) / sigma : (diff == 0 ? 0 : 1e9);
        worstZ = std::max(worstZ, z);
        blocksOff += z > 4.0;
        ++blocks;
      }
    }
  std::printf("%s: %d block-channels, worst |z| = %.2f\n", scenePath.c_str(), blocks, worstZ);
  // Blocks are independent; with 4-sigma bounds a single outlier is already unlikely (~1e-4
  // each), but heavy-tailed caustic noise makes sigma estimates rough: allow one.
  EXPECT_LE(blocksOff, 1) << "worst |z| " << worstZ;
  Color ma = test::meanOf(a), ms = test::meanOf(scalar);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(ma[c] / ms[c], 1.0, 0.03) << "channel " << c;
}

TEST(StatisticalPathVsScalar, CornellBox) {
  compareBlocks(test::sharedScenesDir() + "/cornell-box/scene.xml", 32, 256, 512, 8);
}

TEST(StatisticalPathVsScalar, DefaultScene) {
  compareBlocks(test::sourceDir() + "/scenes/default/scene.xml", 32, 256, 512, 8);
}

}  // namespace
}  // namespace erpt
