// Path tracer stages on small hand-built queues.
#include <gtest/gtest.h>

#include <algorithm>

#include "models/camera.h"
#include "erpt/scene_loader.h"
#include "stages/stages.h"
#include "tracer/tracer.h"
#include "support/test_support.h"

namespace erpt {
namespace {

TEST(StageCompact, KeepsExactlyTheLiveSlotsInOrder) {
  const size_t n = 1000;
  PathSlotQueue slots, outSlots;
  RayQueue rays, outRays;
  slots.resize(n);
  prepareRays(rays, n);
  outSlots.resize(n);
  prepareRays(outRays, n);
  std::vector<uint32_t> expected, expectedEnded;
  for (size_t k = 0; k < n; ++k) {
    slots.path[k] = uint32_t(5000 + k);
    slots.alive[k] = (k * 7919 % 13) < 5;  // an irregular pattern
    setRay(rays, k, Vec3(float(k), 0, 0), Vec3(0, 0, 1), 0.0f, float(k));
    (slots.alive[k] ? expected : expectedEnded).push_back(uint32_t(5000 + k));
  }
  for (size_t grain : {1, 7, 64, 4096}) {
    std::vector<uint32_t> ended(n, 0);
    size_t kept = stageCompact(slots, rays, outSlots, outRays, n, grain, ended.data());
    ASSERT_EQ(kept, expected.size());
    ended.resize(n - kept);
    EXPECT_EQ(ended, expectedEnded) << "grain " << grain;  // the retired path ids, in slot order
    for (size_t j = 0; j < kept; ++j) {
      ASSERT_EQ(outSlots.path[j], expected[j]) << "grain " << grain;
      size_t k = expected[j] - 5000;
      EXPECT_EQ(outRays.orgX[j], float(k));  // the ray moved with its slot
      EXPECT_EQ(outRays.tfar[j], float(k));
    }
  }
  EXPECT_EQ(stageCompact(slots, rays, outSlots, outRays, 0, 64), 0u);
}

// A unit quad at z = 0 blocks exactly the shadow rays that cross it.
TEST(StageShadow, MarksExactlyTheOccludedRays) {
  test::TempDir dir;
  Scene scene = loadScene(dir.write("s.xml", R"(<scene version="3.0.0"><shape type="rectangle"/></scene>)"));
  Tracer tracer(scene);
  RayQueue rays;
  PathSlotQueue slots;
  PathQueue paths;
  const size_t n = 400;
  prepareRays(rays, n);
  slots.resize(n);
  paths.resize(n);
  std::vector<bool> blocked(n);
  for (size_t k = 0; k < n; ++k) {
    // Rays from z = 1 straight down, x and y on a grid over [-2, 2]; half stop above the quad.
    float x = -2 + 4 * float(k % 20) / 19, y = -2 + 4 * float(k / 20) / 19;
    float tfar = (k % 2) ? 2.0f : 0.5f;
    setRay(rays, k, Vec3(x, y, 1), Vec3(0, 0, -1), 0.0f, tfar);
    blocked[k] = std::abs(x) < 1 && std::abs(y) < 1 && tfar > 1;
    slots.path[k] = uint32_t(k);
    slots.neeSet(k, Color(1.0f));
    paths.radianceSet(k, Color(0.0f));
  }
  tracer.occluded(rays, {0, n});
  stageShadowResolve(rays, slots, paths, {0, n});
  for (size_t k = 0; k < n; ++k) EXPECT_EQ(paths.radianceR[k], blocked[k] ? 0.0f : 1.0f) << k;
}

// With spp samples per pixel, the film positions fall into every one of the spp strata in
// x exactly once, and likewise in y (Latin hypercube), for every pixel.
TEST(StageGenerate, FilmPositionsAreStratifiedPerPixel) {
  test::TempDir dir;
  Scene scene = loadScene(dir.write("s.xml", R"(<scene version="3.0.0"><shape type="rectangle"/>
      <sensor type="perspective"><float name="fov" value="90"/><transform name="to_world"><translate z="-3"/></transform>
      <film type="hdrfilm"><integer name="width" value="4"/><integer name="height" value="3"/></film></sensor></scene>)"));
  const int spp = 16, w = 4, h = 3;
  Camera camera(scene.camera, w, h);
  PixelFilter box(FilterKind::Box);
  LightSampler lights(scene);
  StageContext ctx{scene, camera, box, lights, 42, w, h, spp, -1};
  const size_t n = size_t(w) * h * spp;
  std::vector<uint32_t> pixel(n), sample(n);
  for (size_t i = 0; i < n; ++i) {
    pixel[i] = uint32_t(i / spp);
    sample[i] = uint32_t(i % spp);
  }
  RayQueue rays;
  prepareRays(rays, n);
  stageGenerateCameraRays(ctx, pixel.data(), sample.data(), rays, {0, n});
  for (int p = 0; p < w * h; ++p) {
    std::vector<int> xStrata(spp, 0), yStrata(spp, 0);
    for (int s = 0; s < spp; ++s) {
      size_t i = size_t(p) * spp + s;
      // Recover the film position by projecting a point along the ray.
      Vec3 o = rays.orgAt(i), d = rays.dirAt(i);
      float fx, fy;
      ASSERT_TRUE(camera.project(o + d * 2.0f, fx, fy));
      float lx = fx - float(p % w), ly = fy - float(p / w);  // position within the pixel
      ASSERT_GE(lx, -1e-4f);
      ASSERT_LE(lx, 1 + 1e-4f);
      xStrata[std::min(spp - 1, int(lx * spp))]++;
      yStrata[std::min(spp - 1, int(ly * spp))]++;
    }
    for (int k = 0; k < spp; ++k) {
      EXPECT_EQ(xStrata[k], 1) << "pixel " << p << " x-stratum " << k;
      EXPECT_EQ(yStrata[k], 1) << "pixel " << p << " y-stratum " << k;
    }
  }
}

// Sample passes (sample_passes.h) stop after the first k of a pixel's spp samples: those must
// be uniform over the pixel on their own, not just all spp together (with sample s in x
// stratum s, the first quarter of the samples would all lie in the pixel's left quarter).
// Chi-square of the in-pixel offsets of the first k samples of 1024 pixels over 16 bins
// (15 degrees of freedom: mean 15, the bound 40 has p ~ 3e-4).
TEST(StageGenerate, TheFirstSamplesOfEveryPixelAreUniformOverIt) {
  test::TempDir dir;
  Scene scene = loadScene(dir.write("s.xml", R"(<scene version="3.0.0"><shape type="rectangle"/>
      <sensor type="perspective"><float name="fov" value="90"/><transform name="to_world"><translate z="-3"/></transform>
      <film type="hdrfilm"><integer name="width" value="32"/><integer name="height" value="32"/></film></sensor></scene>)"));
  const int spp = 16, w = 32, h = 32, bins = 16;
  Camera camera(scene.camera, w, h);
  PixelFilter box(FilterKind::Box);
  LightSampler lights(scene);
  StageContext ctx{scene, camera, box, lights, 42, w, h, spp, -1};
  for (int first : {1, 4}) {
    SCOPED_TRACE("the first " + std::to_string(first) + " samples");
    const size_t n = size_t(w) * h * first;
    std::vector<uint32_t> pixel(n), sample(n);
    for (size_t i = 0; i < n; ++i) pixel[i] = uint32_t(i % (w * h)), sample[i] = uint32_t(i / (w * h));
    RayQueue rays;
    prepareRays(rays, n);
    std::vector<float> fx(n), fy(n);
    stageGenerateCameraRays(ctx, pixel.data(), sample.data(), rays, {0, n}, fx.data(), fy.data());
    std::vector<double> countX(bins, 0), countY(bins, 0);
    for (size_t i = 0; i < n; ++i) {
      const double lx = fx[i] - double(pixel[i] % w), ly = fy[i] - double(pixel[i] / w);
      countX[std::clamp(int(lx * bins), 0, bins - 1)] += 1;
      countY[std::clamp(int(ly * bins), 0, bins - 1)] += 1;
    }
    const double expected = double(n) / bins;
    double chiX = 0, chiY = 0;
    for (int b = 0; b < bins; ++b) {
      chiX += (countX[b] - expected) * (countX[b] - expected) / expected;
      chiY += (countY[b] - expected) * (countY[b] - expected) / expected;
    }
    EXPECT_LT(chiX, 40.0);
    EXPECT_LT(chiY, 40.0);
  }
}

}  // namespace
}  // namespace erpt
