// Discrete choices are drawn exactly: an index uniform over [0, n) for any n (not only powers
// of two), and coins and CDF inversions with 53-bit numbers. The defect these tests catch:
// MLT's large step chose its pixel as floor(u * pixels) with a 24-bit float u, so at 1920x1080
// 9% of the pixels were drawn 9/8 as often as the others, and its image converged to that
// pattern (W assumed 1 / pixels).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "stages/chain_stages.h"
#include "stages/mlt_stages.h"
#include "core/queues.h"
#include "core/rng.h"

namespace erpt {
namespace {

// The pixels the old choice, min(n - 1, floor(u * n)) in float arithmetic with a 24-bit u,
// favoured: those more of the 2^24 values of u map to (9 rather than 8 at 1920x1080).
std::vector<uint8_t> favouredByFloatFloor(uint32_t n) {
  std::vector<uint32_t> count(n, 0);
  for (uint32_t k = 0; k < (1u << 24); ++k) ++count[std::min(n - 1, uint32_t(float(k) * 0x1p-24f * float(n)))];
  const uint32_t low = *std::min_element(count.begin(), count.end());
  std::vector<uint8_t> favoured(n);
  for (uint32_t p = 0; p < n; ++p) favoured[p] = count[p] > low;
  return favoured;
}

// Fraction of draws that land on the pixels the 24-bit rule favoured: for exact draws it is the
// fraction of such pixels; for the old rule it was about 9/8.09 of that (an 11% excess).
double favouredShare(uint32_t n, const std::vector<uint32_t>& draws, double& expected) {
  const std::vector<uint8_t> favoured = favouredByFloatFloor(n);
  size_t count = 0;
  for (uint32_t p = 0; p < n; ++p) count += favoured[p];
  expected = double(count) / n;
  size_t hits = 0;
  for (uint32_t d : draws) hits += favoured[d];
  return double(hits) / double(draws.size());
}

TEST(ExactDraws, UniformIndexHasNoFloatPatternAt1920x1080) {
  const uint32_t n = 1920 * 1080;
  std::vector<uint32_t> draws(2000000);
  for (size_t i = 0; i < draws.size(); ++i) draws[i] = uint32_t(uniformIndex(streamKey(7, i, 3), 5, n));
  double expected = 0;
  const double share = favouredShare(n, draws, expected);
  const double sigma = std::sqrt(expected * (1 - expected) / double(draws.size()));
  ASSERT_GT(expected, 0.05);  // the favoured pixels exist at this size
  EXPECT_LT(std::abs(share - expected) / sigma, 5.0) << "share " << share << " expected " << expected;
}

// The large step's own pixel choice, through the chain queue as MLT calls it.
TEST(ExactDraws, MltLargeStepPixelIsUniformAt1920x1080) {
  const uint32_t n = 1920 * 1080;
  ChainQueue chains;
  chains.resize(1);
  std::vector<uint32_t> draws(2000000);
  for (size_t i = 0; i < draws.size(); ++i) {
    chains.key[0] = streamKey(11, i, 0);
    chains.step[0] = uint32_t(i % 97);
    uint32_t sample = 0;
    largeStepSample(chains, 0, n, draws[i], sample);
    ASSERT_LT(draws[i], n);
  }
  double expected = 0;
  const double share = favouredShare(n, draws, expected);
  const double sigma = std::sqrt(expected * (1 - expected) / double(draws.size()));
  EXPECT_LT(std::abs(share - expected) / sigma, 5.0) << "share " << share << " expected " << expected;
}

// Where 2^24 / n is below 2 the old rule drew some values twice as often as others, and past
// 2^24 values never at all: every value must keep its 1 / n.
TEST(ExactDraws, UniformIndexChiSquareOnAwkwardSizes) {
  for (uint64_t n : {3ull, 7ull, 1000ull, 12000007ull, 40000003ull}) {
    const size_t bins = 97;  // residues n mod 97 make bins of unequal size; weigh them exactly
    std::vector<double> observed(bins, 0), expected(bins, 0);
    const size_t draws = 1000000;
    for (size_t i = 0; i < draws; ++i) {
      const uint64_t v = uniformIndex(streamKey(n, i, 1), 0, n);
      ASSERT_LT(v, n);
      observed[v % bins] += 1;
    }
    for (size_t b = 0; b < bins; ++b)
      expected[b] = double(draws) * double(n / bins + (b < n % bins ? 1 : 0)) / double(n);
    double chi2 = 0;
    size_t used = 0;
    for (size_t b = 0; b < bins; ++b)
      if (expected[b] > 0) chi2 += (observed[b] - expected[b]) * (observed[b] - expected[b]) / expected[b], ++used;
    // chi-square with used - 1 degrees of freedom: mean k, sd sqrt(2k); 6 sd is far out.
    const double k = double(used - 1);
    EXPECT_LT(chi2, k + 6 * std::sqrt(2 * k)) << "n = " << n;
  }
  // Far above 2^24 the top half of the range must be reachable.
  bool upper = false;
  for (size_t i = 0; i < 64 && !upper; ++i) upper = uniformIndex(streamKey(1, i, 2), 0, 7680ull * 4320 * 4) >= 7680ull * 4320 * 2;
  EXPECT_TRUE(upper);
}

// A coin against a probability below 2^-24 comes up with that probability, not 2^-24 (the
// accept stage's coin, and chains-per-seed for dim seeds).
TEST(ExactDraws, CoinsAgainstTinyProbabilities) {
  const double q = 1e-9;
  size_t heads = 0;
  const size_t flips = 200000000;
  for (size_t i = 0; i < flips; ++i) heads += uniformDouble(i * 0x9e3779b97f4a7c15ull, 0) < q;
  // Expected 0.2 heads; a 24-bit coin gives 2^-24 * 2e8 = 11.9 (Poisson: P(<= 2) = 6e-4).
  EXPECT_LE(heads, 2u);
  // And uniformDouble agrees with uniformFloat in its top 24 bits.
  for (uint32_t d = 0; d < 1000; ++d)
    EXPECT_EQ(float(std::floor(uniformDouble(99, d) * 0x1p24) * 0x1p-24), uniformFloat(99, d)) << d;
}

}  // namespace
}  // namespace erpt
