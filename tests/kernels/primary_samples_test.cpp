// Primary sample space (kernels/primary_samples.h): what a proposal draws, what a chain keeps,
// and the distribution of Kelemen's small-step offsets.
#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>
#include <vector>

#include "core/rng.h"
#include "kernels/primary_samples.h"
#include "kernels/sample_dimensions.h"

namespace erpt {
namespace {

constexpr double kStep = 1.0 / 64;

// The signed offset between two 64-bit fixed-point values on the unit circle, in [-1/2, 1/2).
double circularOffset(uint64_t from, uint64_t to) { return double(int64_t(to - from)) * 0x1p-64; }

TEST(PrimarySamples, ALargeStepDrawsTheAttemptStreamAndReadsAreRepeatable) {
  PrimarySamples p(3, kStep);
  const uint64_t key = streamKey(1, 2, 3);
  p.propose(1, key, true);
  for (uint32_t dim : {kDimFilmX, kDimFilmY, bounceDim(4, kBsdf1), kDimLensY, bounceDim(40, kLobe)}) {
    EXPECT_EQ(p.bits(1, dim), uniformBits(key, dim)) << "dim " << dim;
    EXPECT_EQ(p.bits(1, dim), uniformBits(key, dim)) << "dim " << dim << ", read again";
  }
}

TEST(PrimarySamples, AChainKeepsWhatItsAcceptedProposalRead) {
  PrimarySamples p(2, kStep);
  p.propose(0, streamKey(5, 0, 0), true);
  const uint64_t x = p.bits(0, kDimFilmX), y = p.bits(0, bounceDim(2, kLight1)), lens = p.bits(0, kDimLensX);
  p.bits(0, bounceDim(40, kLobe));  // past the kept slots: never kept
  EXPECT_FALSE(p.keeps(0, kDimFilmX)) << "nothing is kept before an accept";
  p.accept(0);
  EXPECT_TRUE(p.keeps(0, kDimFilmX));
  EXPECT_TRUE(p.keeps(0, bounceDim(2, kLight1)));
  EXPECT_TRUE(p.keeps(0, kDimLensX));
  EXPECT_FALSE(p.keeps(0, kDimFilmY));
  EXPECT_FALSE(p.keeps(0, bounceDim(40, kLobe)));
  EXPECT_FALSE(p.keeps(1, kDimFilmX)) << "another chain";

  // A small step moves the kept numbers by at most s2 and at least s1 = s2 / 16, and draws the
  // others afresh from the attempt's stream.
  const uint64_t key = streamKey(5, 0, 1);
  p.propose(0, key, false);
  for (auto [dim, before] : {std::pair{kDimFilmX, x}, {bounceDim(2, kLight1), y}, {kDimLensX, lens}}) {
    const double d = std::abs(circularOffset(before, p.bits(0, dim)));
    EXPECT_GE(d, kStep / 16 * (1 - 1e-12)) << "dim " << dim;
    EXPECT_LE(d, kStep * (1 + 1e-12)) << "dim " << dim;
  }
  EXPECT_EQ(p.bits(0, kDimFilmY), uniformBits(key, kDimFilmY));
  EXPECT_EQ(p.bits(0, bounceDim(40, kLobe)), uniformBits(key, bounceDim(40, kLobe)));

  // Without an accept the state stays: the next proposal moves from the same values.
  p.propose(0, streamKey(5, 0, 2), false);
  EXPECT_LE(std::abs(circularOffset(x, p.bits(0, kDimFilmX))), kStep * (1 + 1e-12));
  EXPECT_FALSE(p.keeps(0, kDimFilmY));
  // An accepted proposal that read fewer numbers keeps only those.
  p.accept(0);
  EXPECT_TRUE(p.keeps(0, kDimFilmX));
  EXPECT_FALSE(p.keeps(0, bounceDim(2, kLight1)));
}

// A BDPT sample's light subpath draws from its own stream of the chain: its numbers are kept
// in their own slots (the emission sample, the bounces, the lens point), apart from the camera
// subpath's of the same dimension. A chain made for the path tracer keeps no light subpath.
TEST(PrimarySamples, ALightSubpathHasItsOwnNumbers) {
  PrimarySamples p(2, kStep, true);
  const uint64_t light = 1 | kLightSubpathStream;
  p.propose(1, streamKey(9, 1, 0), true);
  const uint32_t dims[] = {kDimEmitPick, kDimEmit1 + 3, bounceDim(1, kLobe), bounceDim(14, kRoulette), kDimLensX};
  for (uint32_t dim : dims) EXPECT_NE(p.bits(light, dim), p.bits(1, dim)) << "dim " << dim;
  p.accept(1);
  for (uint32_t dim : dims) {
    EXPECT_TRUE(p.keeps(light, dim)) << "dim " << dim;
    // The emission sample is the light subpath's alone: the camera's stream keeps no slot for it.
    EXPECT_EQ(p.keeps(1, dim), dim < kDimEmitPick || dim >= kDimEmitPick + kEmitDims) << "dim " << dim;
  }
  EXPECT_FALSE(p.keeps(light, kDimEmit1 + 4)) << "not read";
  EXPECT_FALSE(p.keeps(0 | kLightSubpathStream, kDimEmitPick)) << "another chain";

  PrimarySamples pathOnly(1, kStep);
  pathOnly.propose(0, streamKey(9, 0, 0), true);
  pathOnly.bits(kLightSubpathStream, kDimEmitPick);
  pathOnly.accept(0);
  EXPECT_FALSE(pathOnly.keeps(kLightSubpathStream, kDimEmitPick));
}

// The offset's magnitude is s2 (s1 / s2)^u: its logarithm is uniform between log s1 and
// log s2 (chi-square over 20 bins), and its sign is a fair coin, so the step is symmetric.
TEST(PrimarySamples, SmallStepOffsetsAreLogUniformAndSymmetric) {
  const PrimarySamples p(1, kStep);
  constexpr int kBins = 20, kDraws = 200000;
  std::vector<int> bins(kBins, 0);
  int positive = 0;
  for (int i = 0; i < kDraws; ++i) {
    const uint64_t offset = p.smallStepOffset(uniformBits(77, uint32_t(i)));
    const double d = circularOffset(0, offset);
    positive += d > 0;
    const double u = std::log(kStep / std::abs(d)) / std::log(16.0);  // uniform in [0, 1)
    ASSERT_GE(u, -1e-9);
    ASSERT_LT(u, 1 + 1e-9);
    ++bins[std::min(kBins - 1, int(u * kBins))];
  }
  double chi2 = 0;
  const double expected = double(kDraws) / kBins;
  for (int c : bins) chi2 += (c - expected) * (c - expected) / expected;
  EXPECT_LT(chi2, 43.8) << "chi-square with 19 degrees of freedom, p = 0.001";
  EXPECT_LT(std::abs(positive - kDraws / 2) / std::sqrt(kDraws / 4.0), 4.0) << positive << " positive offsets";
}

// mmlt's normal offsets (the ziggurat, kernels/normal_ziggurat.h): sigma z with z standard
// normal. Chi-square of z over 24 bins equally likely under the normal (their edges from the
// inverse of erfc), the tail beyond the ziggurat's base layer (|z| > 3.44) in its own bin, and
// the sign a fair coin, so the step is symmetric.
TEST(PrimarySamples, NormalOffsetsAreNormalAndSymmetric) {
  const double sigma = 0.01;
  const PrimarySamples p(1, sigma, false, StepKind::Normal);
  constexpr int kBins = 24, kDraws = 400000;
  // Bin edges of |z|: P(|z| < e_k) = k / kBins, by bisection on erf.
  std::vector<double> edges;
  for (int k = 1; k < kBins; ++k) {
    double lo = 0, hi = 10;
    for (int it = 0; it < 100; ++it) {
      const double mid = 0.5 * (lo + hi);
      (std::erf(mid / std::sqrt(2.0)) < double(k) / kBins ? lo : hi) = mid;
    }
    edges.push_back(lo);
  }
  std::vector<int> bins(kBins, 0);
  int positive = 0, tail = 0;
  for (int i = 0; i < kDraws; ++i) {
    const double z = circularOffset(0, p.smallStepOffset(uniformBits(78, uint32_t(i)))) / sigma;
    positive += z > 0;
    tail += std::abs(z) > 3.442619855899;
    ++bins[size_t(std::upper_bound(edges.begin(), edges.end(), std::abs(z)) - edges.begin())];
  }
  double chi2 = 0;
  const double expected = double(kDraws) / kBins;
  for (int c : bins) chi2 += (c - expected) * (c - expected) / expected;
  EXPECT_LT(chi2, 49.7) << "chi-square with 23 degrees of freedom, p = 0.001";
  // P(|z| > 3.4426) = 5.76e-4: the base layer's tail is drawn at its rate.
  const double tailExpected = kDraws * std::erfc(3.442619855899 / std::sqrt(2.0));
  EXPECT_LT(std::abs(tail - tailExpected) / std::sqrt(tailExpected), 4.0) << tail << " beyond the base layer";
  EXPECT_LT(std::abs(positive - kDraws / 2) / std::sqrt(kDraws / 4.0), 4.0) << positive << " positive offsets";
}

}  // namespace
}  // namespace erpt
