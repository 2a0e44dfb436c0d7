// PMC-ER's pool of film positions: every pixel sample of the render exactly once, each pixel's
// samples in distinct strata, and any prefix spread evenly over the image.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "stages/stages.h"
#include "integrators/pmc_er/stratified_pool.h"
#include "support/erpt_world.h"
#include "support/test_support.h"

namespace erpt {
namespace {

TEST(PmcPool, EveryPositionOnceAndEachPixelStratified) {
  const int size = 24;
  const uint32_t spp = 8;
  test::ErptWorld w(test::sharedScenesDir() + "/cornell-box/scene.xml", size, 1, FilterKind::Box);
  const StageContext ctx{w.scene, *w.camera, *w.filter, *w.lights, 5, size, size, int(spp), -1};
  const StratifiedPool pool{uint32_t(size * size), spp, 99};
  ASSERT_EQ(pool.size(), size_t(size * size) * spp);
  std::vector<uint32_t> pixels(pool.size()), samples(pool.size());
  for (size_t k = 0; k < pool.size(); ++k) pool.at(k, pixels[k], samples[k]);
  // No (pixel, sample) twice: the pool is a bijection onto all pixel samples.
  std::vector<int> used(pool.size(), 0);
  for (size_t k = 0; k < pool.size(); ++k) {
    ASSERT_LT(pixels[k], uint32_t(size * size));
    ASSERT_LT(samples[k], spp);
    ++used[size_t(pixels[k]) * spp + samples[k]];
  }
  for (int u : used) ASSERT_EQ(u, 1);
  // The film positions the path tracer makes of them: per pixel, one in each x stratum and
  // one in each y stratum (box filter: the offset in the pixel is the stratified sample).
  RayQueue rays;
  prepareRays(rays, pool.size());
  std::vector<float> fx(pool.size()), fy(pool.size());
  stageGenerateCameraRays(ctx, pixels.data(), samples.data(), rays, IndexRange{0, pool.size()}, fx.data(), fy.data());
  // Sorted, the i-th offset of a pixel lies in stratum i (up to the float rounding of
  // pixel + offset, ~5e-7 pixels).
  std::vector<std::vector<double>> xs(size_t(size * size)), ys = xs;
  for (size_t k = 0; k < pool.size(); ++k) {
    const uint32_t p = pixels[k];
    xs[p].push_back((fx[k] - double(p % uint32_t(size))) * spp);
    ys[p].push_back((fy[k] - double(p / uint32_t(size))) * spp);
  }
  for (auto* offsets : {&xs, &ys})
    for (size_t p = 0; p < offsets->size(); ++p) {
      std::vector<double>& o = (*offsets)[p];
      ASSERT_EQ(o.size(), spp);
      std::sort(o.begin(), o.end());
      for (uint32_t i = 0; i < spp; ++i) {
        ASSERT_GE(o[i], i - 1e-4) << "pixel " << p;
        ASSERT_LE(o[i], i + 1 + 1e-4) << "pixel " << p;
      }
    }
  // A prefix of any length covers the image evenly: after k positions every pixel has
  // floor(k / pixels) or one more.
  std::vector<int> seen(size_t(size * size), 0);
  for (size_t k = 0; k < pool.size(); ++k) {
    ++seen[pixels[k]];
    if (k % 97 == 0) {
      for (int c : seen) ASSERT_LE(std::abs(c - int((k + 1) / size_t(size * size))), 1);
    }
  }
}

}  // namespace
}  // namespace erpt
