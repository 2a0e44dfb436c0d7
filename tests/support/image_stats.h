// Image comparisons used by the statistical tests (the library's metrics, under short names).
#pragma once

#include <vector>

#include "erpt/image_metrics.h"

namespace erpt::test {

using erpt::meanOf;
// Mean over pixels and channels of (x - r)^2 / (r^2 + 0.01); sizes must agree.
double relativeMse(const RgbImage& img, const RgbImage& ref);

// Block-by-block comparison of two estimators from independent renders of each: per block of
// block x block pixels, Welch's z = (mean_a - mean_b) / sqrt(var_a / n_a + var_b / n_b) on
// the block's luminance, with the variances estimated from the runs. Unbiased estimators give
// z^2 near 1 on average (a little more: the variances are estimated); a bias that moves energy
// between regions gives large |z| in some blocks even when the image means agree.
struct BlockZScores {
  std::vector<double> z;  // one per block with energy, row-major
  double meanSquare = 0;  // mean of z^2
  double worst = 0;       // max |z|
  // The second set's part of the z denominators (its variance of the mean over the sum of
  // both), averaged over the blocks: how much a noisier reference costs the test in power.
  double secondShare = 0;
};
// relMSE of every image against the mean of the others (pixel and channel-wise, with the usual
// 0.01 in the denominator): each run's error without a stored reference.
std::vector<double> leaveOneOutRelMse(const std::vector<RgbImage>& images);

// Same size and every channel of every pixel equal, bit for bit (gtest failures otherwise).
void expectBitIdentical(const RgbImage& a, const RgbImage& b);

BlockZScores blockZScores(const std::vector<RgbImage>& a, const std::vector<RgbImage>& b, int block);

// The same in two steps: each set's per-block mean luminance sum and the variance of that mean
// (so that one side can be stored: support/block_bias.h).
struct BlockStats {
  std::vector<double> mean, varianceOfMean;
};
BlockStats blockStats(const std::vector<RgbImage>& runs, int block);
BlockZScores blockZScores(const BlockStats& a, const BlockStats& b);

}  // namespace erpt::test
