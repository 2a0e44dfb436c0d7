// PMC-ER's mixture weights: the adaptation rule, the choice of a component, the region table
// and the selection ratio the acceptance multiplies in.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <vector>

#include "stages/pmc_mixture.h"
#include "core/rng.h"

namespace erpt {
namespace {

float sum(const float* a, int k) { return std::accumulate(a, a + k, 0.0f); }

TEST(PmcAlpha, MovesToTheRadiusAcceptedMostAndKeepsTheFloor) {
  float a[3];
  const double sums[3] = {50, 5, 1};
  alphaFromAcceptance(sums, 3, 0.05f, a);
  EXPECT_GT(a[0], a[1]);
  EXPECT_GT(a[1], a[2]);
  EXPECT_NEAR(sum(a, 3), 1.0f, 1e-6f);
  EXPECT_NEAR(a[0], 0.05f + 0.85f * 50.0f / 56.0f, 1e-6f);
  const double one[3] = {1000, 0, 0};
  alphaFromAcceptance(one, 3, 0.05f, a);
  EXPECT_FLOAT_EQ(a[1], 0.05f);  // never below eps
  EXPECT_FLOAT_EQ(a[2], 0.05f);
  EXPECT_NEAR(a[0], 0.9f, 1e-6f);
}

TEST(PmcAlpha, NewMembersStartUniform) {
  float a[4];
  const double none[4] = {0, 0, 0, 0};
  alphaFromAcceptance(none, 4, 0.05f, a);
  for (float v : a) EXPECT_FLOAT_EQ(v, 0.25f);
}

TEST(PmcAlpha, PickComponentFollowsTheWeights) {
  const float a[3] = {0.6f, 0.3f, 0.1f};
  int counts[3] = {};
  const int n = 200000;
  for (int i = 0; i < n; ++i) ++counts[pickComponent(a, 3, uniformFloat(streamKey(7, 0, 0), uint32_t(i)))];
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(double(counts[k]) / n, a[k], 4 * std::sqrt(a[k] * (1 - a[k]) / n));
}

// A synthetic population: a member's proposals with radius k are accepted with probability
// p_k (radius 0 far more often); the paper's rule, applied after every iteration of 16
// proposals, moves alpha to radius 0, never below eps on the others.
TEST(PmcAlpha, SyntheticPopulationMovesAlphaToTheRadiusAcceptedMost) {
  const double p[3] = {0.8, 0.2, 0.05};
  const int members = 200;
  double meanAlpha0 = 0, minAlpha = 1;
  for (int m = 0; m < members; ++m) {
    double sums[3] = {};
    float a[3];
    alphaFromAcceptance(sums, 3, 0.05f, a);  // a new member: uniform
    EXPECT_FLOAT_EQ(a[0], 1.0f / 3);
    uint32_t dim = 0;
    for (int it = 0; it < 8; ++it) {
      for (int t = 0; t < 16; ++t) {
        const int k = pickComponent(a, 3, uniformFloat(streamKey(11, uint64_t(m), 0), dim++));
        sums[k] += uniformFloat(streamKey(11, uint64_t(m), 1), dim++) < p[k] ? 1.0 : 0.0;  // an acceptance
      }
      alphaFromAcceptance(sums, 3, 0.05f, a);
      for (float v : a) minAlpha = std::min(minAlpha, double(v));
    }
    meanAlpha0 += a[0] / members;
  }
  EXPECT_GT(meanAlpha0, 0.8);
  EXPECT_GE(minAlpha, 0.05 - 1e-7);
}

TEST(PmcRegionTable, WeightsPerRegionAndSelectionRatio) {
  PmcSettings s;
  s.adapt = PmcAdapt::Region;
  s.regionSize = 8;
  PmcMixture mix(s, 32, 16);  // 4 x 2 regions
  ASSERT_EQ(mix.regionCount(), 8);
  EXPECT_EQ(mix.regionOf(3.5f, 2.0f), 0);
  EXPECT_EQ(mix.regionOf(9.0f, 9.0f), 5);
  EXPECT_EQ(mix.regionOf(-4.0f, 100.0f), 4);  // clamped to the border
  std::vector<double> sums(8 * 3, 0.0);
  sums[5 * 3 + 2] = 100;  // region 5 accepted radius 50 often
  mix.setRegionTable(sums, 1.0);
  const float* a5 = mix.weightsFor(0, 9.0f, 9.0f);
  const float* a0 = mix.weightsFor(0, 1.0f, 1.0f);
  EXPECT_GT(a5[2], 0.8f);
  EXPECT_NEAR(a0[2], 1.0f / 3, 1e-6f);  // prior only: uniform
  EXPECT_NEAR(sum(a5, 3), 1.0f, 1e-6f);

  // A chain in region 0 whose complete radius-50 proposal lands in region 5.
  ChainQueue chains;
  chains.resize(1);
  chains.filmX[0] = 1.0f;
  chains.filmY[0] = 1.0f;
  ProposalQueue proposals;
  proposals.resize(1);
  proposals.state[0] = kProposalComplete;
  proposals.component[0] = 2;
  proposals.filmX[0] = 9.0f;
  proposals.filmY[0] = 9.0f;
  proposals.selection[0] = 1;
  mix.selectionRatios(chains, proposals, IndexRange{0, 1});
  EXPECT_NEAR(proposals.selection[0], a5[2] / a0[2], 1e-6f);
}

}  // namespace
}  // namespace erpt
