#include "support/closed_form_check.h"

#include <gtest/gtest.h>

#include <cmath>

#include "models/camera.h"
#include "support/image_stats.h"

namespace erpt::test {

namespace {
constexpr double kRoundingShare = 1e-4;
}  // namespace

RgbImage exactImage(const Scene& scene, int width, int height, int subdivisions,
                    const std::function<Color(Vec3 origin, Vec3 direction)>& radiance) {
  const Camera camera(scene.camera, width, height);
  RgbImage img;
  img.width = width;
  img.height = height;
  img.pixels.assign(size_t(width) * size_t(height), Color(0.0f));
  const double n2 = double(subdivisions) * subdivisions;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      double r = 0, g = 0, b = 0;
      for (int j = 0; j < subdivisions; ++j)
        for (int i = 0; i < subdivisions; ++i) {
          const Camera::Ray ray = camera.generateRay(float(x + (i + 0.5) / subdivisions), float(y + (j + 0.5) / subdivisions));
          const Color c = radiance(ray.origin, ray.direction);
          r += c.x, g += c.y, b += c.z;
        }
      img.at(x, y) = Color(float(r / n2), float(g / n2), float(b / n2));
    }
  return img;
}

ClosedFormResult compareWithClosedForm(const Scene& scene, const RenderSettings& settings, const RgbImage& exact,
                                       int runs, uint64_t seed, int block) {
  std::vector<RgbImage> images;
  std::vector<double> ratios;
  double exactSum = 0;
  for (const Color& c : exact.pixels) exactSum += luminance(c);
  for (int k = 0; k < runs; ++k) {
    RenderSettings s = settings;
    s.seed = seed + uint64_t(k);
    RenderStats stats;
    images.push_back(render(scene, s, stats));
    EXPECT_EQ(stats.invalidSamples, 0u);
    EXPECT_EQ(images.back().width, exact.width);
    EXPECT_EQ(images.back().height, exact.height);
    double sum = 0;
    for (const Color& c : images.back().pixels) sum += luminance(c);
    ratios.push_back(sum / exactSum);
  }
  ClosedFormResult out;
  double mean = 0, spread = 0;
  for (double r : ratios) mean += r / runs;
  for (double r : ratios) spread += (r - mean) * (r - mean);
  out.ratio = mean;
  out.ratioError = std::sqrt(spread / (runs - 1) / runs);
  // The exact side carries a variance of its own: float rounding, 1e-4 of each block (renders
  // of a constant image, such as a glass sphere in a white furnace, scatter by 1e-5 and less,
  // and their standard error can be smaller still).
  BlockStats exactStats = blockStats({exact, exact}, block);
  for (size_t k = 0; k < exactStats.mean.size(); ++k)
    exactStats.varianceOfMean[k] = kRoundingShare * kRoundingShare * exactStats.mean[k] * exactStats.mean[k];
  out.ratioError = std::sqrt(out.ratioError * out.ratioError + kRoundingShare * kRoundingShare);
  const BlockZScores z = blockZScores(blockStats(images, block), exactStats);
  out.meanSquare = z.meanSquare;
  out.worst = z.worst;
  out.blocks = int(z.z.size());
  return out;
}

}  // namespace erpt::test
