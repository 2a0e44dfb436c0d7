#include "support/image_stats.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace erpt::test {

double relativeMse(const RgbImage& img, const RgbImage& ref) {
  if (img.width != ref.width || img.height != ref.height) throw std::runtime_error("relativeMse: size mismatch");
  return compareImages(img, ref).relMse;
}

namespace {

// Luminance summed over each block, one vector per image.
std::vector<double> blockSums(const RgbImage& img, int block) {
  const int bw = img.width / block, bh = img.height / block;
  std::vector<double> sums(size_t(bw) * size_t(bh), 0.0);
  for (int y = 0; y < bh * block; ++y)
    for (int x = 0; x < bw * block; ++x) sums[size_t(y / block) * size_t(bw) + size_t(x / block)] += luminance(img.at(x, y));
  return sums;
}

struct MeanVariance {
  double mean = 0, varianceOfMean = 0;
};
// Mean over runs of block k and the variance of that mean (sample variance / runs).
MeanVariance ofRuns(const std::vector<std::vector<double>>& runs, size_t k) {
  const double n = double(runs.size());
  double sum = 0, sum2 = 0;
  for (const auto& r : runs) sum += r[k];
  const double mean = sum / n;
  for (const auto& r : runs) sum2 += (r[k] - mean) * (r[k] - mean);
  return {mean, sum2 / (n - 1) / n};
}

}  // namespace

BlockZScores blockZScores(const std::vector<RgbImage>& a, const std::vector<RgbImage>& b, int block) {
  if (a.size() < 2 || b.size() < 2) throw std::runtime_error("blockZScores: need at least two runs of each");
  std::vector<std::vector<double>> sa, sb;
  for (const RgbImage& i : a) sa.push_back(blockSums(i, block));
  for (const RgbImage& i : b) sb.push_back(blockSums(i, block));
  for (const auto& s : sa)
    if (s.size() != sb[0].size()) throw std::runtime_error("blockZScores: size mismatch");
  for (const auto& s : sb)
    if (s.size() != sb[0].size()) throw std::runtime_error("blockZScores: size mismatch");
  BlockZScores out;
  for (size_t k = 0; k < sb[0].size(); ++k) {
    const MeanVariance ma = ofRuns(sa, k), mb = ofRuns(sb, k);
    const double v = ma.varianceOfMean + mb.varianceOfMean;
    if (!(v > 0)) continue;  // a black block in both
    const double z = (ma.mean - mb.mean) / std::sqrt(v);
    out.z.push_back(z);
    out.meanSquare += z * z;
    out.worst = std::max(out.worst, std::abs(z));
  }
  if (!out.z.empty()) out.meanSquare /= double(out.z.size());
  return out;
}

void expectBitIdentical(const RgbImage& a, const RgbImage& b) {
  ASSERT_EQ(a.width, b.width);
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    ASSERT_EQ(a.pixels[i].x, b.pixels[i].x) << "pixel " << i;
    ASSERT_EQ(a.pixels[i].y, b.pixels[i].y) << "pixel " << i;
    ASSERT_EQ(a.pixels[i].z, b.pixels[i].z) << "pixel " << i;
  }
}

}  // namespace erpt::test
