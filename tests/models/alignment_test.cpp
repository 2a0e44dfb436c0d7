// The camera lines up pixel for pixel with the shared Cornell box reference (rendered by
// Tungsten from the same scene): the ceiling light, the brightest thing in view, must cover
// the same pixels in our render (emitters only, --max-depth 1) as in the reference.
#include <gtest/gtest.h>

#include "erpt/render.h"
#include "erpt/scene_loader.h"
#include "support/test_support.h"

namespace erpt {
namespace {

TEST(Alignment, CornellLightCoversTheSamePixelsAsTheReference) {
  const std::string dir = test::sharedScenesDir() + "/cornell-box";
  RgbImage ref = readImage(dir + "/TungstenRender.exr");
  ASSERT_EQ(ref.width, 1024);
  const int size = 256, factor = ref.width / size;
  Scene scene = loadScene(dir + "/scene.xml");
  RenderSettings s;
  s.integrator = "direct";
  s.width = s.height = size;
  s.spp = 16;
  s.maxDepth = 1;
  s.filterSet = true;
  s.filter = FilterKind::Box;
  RenderStats stats;
  RgbImage ours = render(scene, s, stats);

  // A pixel is "light" when more than half of it is covered by the emitter (luminance 12.5,
  // against < 1.5 for everything else in view).
  const float threshold = 0.5f * luminance(Color(17, 12, 4));
  int both = 0, onlyOurs = 0, onlyRef = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      double sum = 0;
      for (int j = 0; j < factor; ++j)
        for (int i = 0; i < factor; ++i) sum += luminance(ref.at(x * factor + i, y * factor + j));
      bool refLight = sum / (factor * factor) > threshold;
      bool ourLight = luminance(ours.at(x, y)) > threshold;
      both += refLight && ourLight;
      onlyOurs += ourLight && !refLight;
      onlyRef += refLight && !ourLight;
    }
  EXPECT_GT(both, 300);  // the light spans roughly 70 x 8 pixels here
  // Only pixels straddling the light's outline may disagree (a 1-pixel shift would flip
  // a whole edge row: ~70 pixels).
  EXPECT_LE(onlyOurs + onlyRef, 20) << "both " << both << ", only ours " << onlyOurs << ", only reference " << onlyRef;
}

}  // namespace
}  // namespace erpt
