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

}  // namespace

BlockStats blockStats(const std::vector<RgbImage>& runs, int block) {
  if (runs.size() < 2) throw std::runtime_error("blockStats: need at least two runs");
  std::vector<std::vector<double>> sums;
  for (const RgbImage& i : runs) sums.push_back(blockSums(i, block));
  for (const auto& s : sums)
    if (s.size() != sums[0].size()) throw std::runtime_error("blockStats: size mismatch");
  const double n = double(runs.size());
  BlockStats out;
  for (size_t k = 0; k < sums[0].size(); ++k) {
    double sum = 0, sum2 = 0;
    for (const auto& r : sums) sum += r[k];
    const double mean = sum / n;
    for (const auto& r : sums) sum2 += (r[k] - mean) * (r[k] - mean);
    out.mean.push_back(mean);
    out.varianceOfMean.push_back(sum2 / (n - 1) / n);  // sample variance / runs
  }
  return out;
}

BlockZScores blockZScores(const BlockStats& a, const BlockStats& b) {
  if (a.mean.size() != b.mean.size()) throw std::runtime_error("blockZScores: size mismatch");
  BlockZScores out;
  for (size_t k = 0; k < a.mean.size(); ++k) {
    const double v = a.varianceOfMean[k] + b.varianceOfMean[k];
    if (!(v > 0)) continue;  // a black block in both
    const double z = (a.mean[k] - b.mean[k]) / std::sqrt(v);
    out.secondShare += b.varianceOfMean[k] / v;
    out.z.push_back(z);
    out.meanSquare += z * z;
    out.worst = std::max(out.worst, std::abs(z));
  }
  if (!out.z.empty()) out.meanSquare /= double(out.z.size()), out.secondShare /= double(out.z.size());
  return out;
}

BlockZScores blockZScores(const std::vector<RgbImage>& a, const std::vector<RgbImage>& b, int block) {
  return blockZScores(blockStats(a, block), blockStats(b, block));
}

std::vector<double> leaveOneOutRelMse(const std::vector<RgbImage>& images) {
  const size_t n = images.size(), pixels = images[0].pixels.size();
  std::vector<double> sum(pixels * 3, 0.0), result;
  for (const RgbImage& im : images)
    for (size_t p = 0; p < pixels; ++p)
      for (int c = 0; c < 3; ++c) sum[3 * p + size_t(c)] += im.pixels[p][c];
  for (const RgbImage& im : images) {
    double e = 0;
    for (size_t p = 0; p < pixels; ++p)
      for (int c = 0; c < 3; ++c) {
        const double own = im.pixels[p][c], others = (sum[3 * p + size_t(c)] - own) / double(n - 1);
        e += (own - others) * (own - others) / (others * others + 0.01);
      }
    result.push_back(e / double(pixels * 3));
  }
  return result;
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
