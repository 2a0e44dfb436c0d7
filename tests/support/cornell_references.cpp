#include "support/cornell_references.h"

#include <gtest/gtest.h>

#include <cstdio>

#include "erpt/image_io.h"
#include "erpt/scene_loader.h"
#include "support/image_stats.h"
#include "support/test_support.h"

namespace erpt::test {

Scene cornellBox() { return loadScene(sharedScenesDir() + "/cornell-box/scene.xml"); }

void expectCornellBoxConverges(const RgbImage& low, const RgbImage& high, double minRatio, double maxRatio,
                               double meanTolerance) {
  const std::string dir = sharedScenesDir() + "/cornell-box";
  const RgbImage tungsten = readImage(dir + "/TungstenRender.exr");
  const RgbImage ref = readImage(dir + "/reference-box-128.exr");
  const Color m = meanOf(high), r = meanOf(tungsten);
  std::printf("means %.4f %.4f %.4f vs %.4f %.4f %.4f\n", m.x, m.y, m.z, r.x, r.y, r.z);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(m[c] / r[c], 1.0, meanTolerance) << "channel " << c;
  const double ea = relativeMse(low, ref), eb = relativeMse(high, ref);
  std::printf("relMSE %.3g -> %.3g, ratio %.2f\n", ea, eb, ea / eb);
  EXPECT_GT(ea / eb, minRatio);
  EXPECT_LT(ea / eb, maxRatio);
}

}  // namespace erpt::test
