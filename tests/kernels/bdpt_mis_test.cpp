// BDPT's MIS weights (kernels/bdpt_mis.h): over the strategies that can make a path, they sum
// to 1 whatever its densities, Dirac vertices and light type; that is what keeps BDPT unbiased.
#include <gtest/gtest.h>

#include <vector>

#include "core/rng.h"
#include "kernels/bdpt_mis.h"

namespace erpt {
namespace {

struct RandomPath {
  std::vector<float> camera, light;
  std::vector<uint8_t> specular;
  BdptMisPath path;
};

// A path of k segments with densities spread over six decades, some Dirac vertices, and a
// light that may be a point or directional light (not hittable).
RandomPath randomPath(uint64_t key, int k) {
  RandomPath r;
  uint32_t dim = 0;
  auto density = [&] { return float(std::pow(10.0, 6 * uniformDouble(key, dim++) - 3)); };
  for (int i = 0; i <= k; ++i) {
    r.camera.push_back(density());
    r.light.push_back(density());
    r.specular.push_back(i > 0 && i < k && uniformDouble(key, dim++) < 0.25);
  }
  r.path.k = k;
  r.path.cameraDensity = r.camera.data();
  r.path.lightDensity = r.light.data();
  r.path.specular = r.specular.data();
  r.path.nextEventDensity = density();
  r.path.lightHittable = uniformDouble(key, dim++) < 0.7;
  r.path.lightSeenByLightTracing = r.path.lightHittable && uniformDouble(key, dim++) < 0.7;
  return r;
}

TEST(BdptMis, WeightsOfEveryPathSumToOne) {
  int checked = 0;
  for (uint64_t n = 0; n < 4000; ++n) {
    const int k = 1 + int(uniformIndex(streamKey(5, n, 0), 0, 9));
    const RandomPath r = randomPath(streamKey(5, n, 1), k);
    double sum = 0;
    int possible = 0;
    for (int s = 0; s <= k + 1; ++s) {
      if (!bdptStrategyPossible(r.path, s)) continue;
      ++possible;
      sum += bdptMisWeight(r.path, s);
    }
    if (possible == 0) continue;
    ++checked;
    ASSERT_NEAR(sum, 1.0, 1e-5) << "path " << n << " of " << k << " segments, " << possible << " strategies";
  }
  EXPECT_GT(checked, 3000);
}

TEST(BdptMis, WhichStrategiesArePossible) {
  RandomPath r = randomPath(17, 4);
  std::fill(r.specular.begin(), r.specular.end(), 0);
  r.path.lightHittable = true;
  for (int s = 0; s <= 4; ++s) EXPECT_TRUE(bdptStrategyPossible(r.path, s)) << s;
  EXPECT_FALSE(bdptStrategyPossible(r.path, 5));  // t = 0: the camera is never hit
  r.specular[2] = 1;                             // a Dirac lobe at x_2: no connection there
  EXPECT_FALSE(bdptStrategyPossible(r.path, 2));  // x_2 -- x_3
  EXPECT_FALSE(bdptStrategyPossible(r.path, 3));  // x_1 -- x_2
  EXPECT_TRUE(bdptStrategyPossible(r.path, 1));
  r.path.lightHittable = false;  // a point light
  EXPECT_FALSE(bdptStrategyPossible(r.path, 0));
}

// With two strategies of equal densities except one vertex, the power heuristic's weights.
TEST(BdptMis, PowerHeuristicOfTwoStrategies) {
  // k = 1: s = 0 (the camera ray hits the light, density cameraDensity[1]) against s = 1 (the
  // light point joined to the camera, density lightDensity[1]).
  std::vector<float> camera = {1, 2}, light = {0, 6};
  std::vector<uint8_t> specular = {0, 0};
  BdptMisPath p;
  p.k = 1;
  p.cameraDensity = camera.data();
  p.lightDensity = light.data();
  p.specular = specular.data();
  EXPECT_NEAR(bdptMisWeight(p, 0), 4.0 / 40.0, 1e-6);
  EXPECT_NEAR(bdptMisWeight(p, 1), 36.0 / 40.0, 1e-6);
  p.lightSeenByLightTracing = false;
  EXPECT_NEAR(bdptMisWeight(p, 0), 1.0, 1e-6);
}

}  // namespace
}  // namespace erpt
