// No outlier runs of PMC-ER's own, on a bulb inside a glass shade (tests/data/lamp-shade.xml:
// every light path leaves through four refractions, and next-event estimation never gets
// through, so the path-traced seeds are few and heavy-tailed). A run whose energy sits in one
// pixel (a member that cannot move, split into many copies and deposited in place) has a
// relative MSE many times the others'; docs/pmc-er.md, "Outlier runs", says what we found.
// Each run's relMSE is taken against the mean of the other runs of its integrator (no stored
// reference), on an image that is not a power of two in either side.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "erpt/render.h"
#include "erpt/scene_loader.h"
#include "support/block_bias.h"
#include "support/image_stats.h"
#include "support/test_support.h"

namespace erpt {
namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return (v[(v.size() - 1) / 2] + v[v.size() / 2]) / 2;
}

std::vector<RgbImage> renders(const std::string& integrator, int spp, uint64_t firstSeed, int runs) {
  const Scene scene = loadScene(test::sourceDir() + "/tests/data/lamp-shade.xml");
  std::vector<RgbImage> images;
  for (int k = 0; k < runs; ++k) {
    RenderSettings s;
    s.integrator = integrator;
    s.width = 45;
    s.height = 39;
    s.spp = spp;
    s.seed = firstSeed + uint64_t(k);
    images.push_back(test::renderImage(scene, resolveSettings(scene, s)));
  }
  return images;
}

// PMC-ER's pool and ERPT's seeds are the same path-traced samples for the same seed, so the
// seeds' own heavy tail (here a caustic seed holding 2% of the image in one pixel, seed 3107)
// is in both; what PMC-ER does with them must add none of its own. Measured: per seed,
// PMC-ER's relMSE is 0.90-2.0 of ERPT's (1.87 on seed 3107, 2.0 on 3102); medians 1.74 and
// 1.59. With members that cannot move (--radii 3000) runs reach 9 times ERPT's.
TEST(StatisticalOutliers, PmcErAddsNoOutlierToItsSeeds) {
  const int runs = 10;
  const std::vector<double> pmc = test::leaveOneOutRelMse(renders("pmc-er", 8, 3100, runs));
  const std::vector<double> erpt = test::leaveOneOutRelMse(renders("erpt", 8, 3100, runs));
  for (int k = 0; k < runs; ++k)
    EXPECT_LT(pmc[size_t(k)], 3.0 * erpt[size_t(k)])
        << "seed " << 3100 + k << ": PMC-ER relMSE " << pmc[size_t(k)] << ", ERPT " << erpt[size_t(k)];
  // And no worse overall than by the noise between two integrators on ten runs.
  EXPECT_LT(median(pmc), 1.5 * median(erpt));
}

}  // namespace
}  // namespace erpt
