// PMC-ER's resampling keeps every member's expected energy and the total exactly
// (systematic_resampling.h): the image stays unbiased whatever the comb does to one render.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <vector>

#include "integrators/systematic_resampling.h"

namespace erpt {
namespace {

// Hand-built: tiny, zero, equal and dominant energies; fewer slots than members, so most
// members can only survive by chance, and one is split.
const std::vector<double> kEnergies{0.1, 2.5, 0.0, 7.0, 0.4, 1e-3, 0.4, 3.3, 0.0, 0.05};

TEST(PmcResampling, EveryCombGivesExactlyTheSlotsAndKeepsTheTotal) {
  const double total = std::accumulate(kEnergies.begin(), kEnergies.end(), 0.0);
  for (size_t slots : {1u, 3u, 5u, 10u, 37u}) {
    for (int j = 0; j < 1000; ++j) {
      const std::vector<uint32_t> c = systematicCounts(kEnergies, slots, (j + 0.5) / 1000.0);
      EXPECT_EQ(std::accumulate(c.begin(), c.end(), size_t(0)), slots);
      // Each copy carries total / slots: the energy after elimination is the energy before.
      double after = 0;
      for (size_t i = 0; i < c.size(); ++i) after += c[i] * total / double(slots);
      EXPECT_NEAR(after, total, 1e-12 * total);
      EXPECT_EQ(c[2], 0u);  // zero energy never survives
      EXPECT_EQ(c[8], 0u);
    }
  }
}

// E[count_i] * total / slots = w_i: the counts are piecewise constant in u with at most
// members + slots steps, so the midpoint rule over 200000 values of u is exact to ~1e-4.
TEST(PmcResampling, ExpectedEnergyOfEveryMemberIsKept) {
  const double total = std::accumulate(kEnergies.begin(), kEnergies.end(), 0.0);
  for (size_t slots : {3u, 5u, 37u}) {
    std::vector<double> mean(kEnergies.size(), 0.0);
    const int steps = 200000;
    for (int j = 0; j < steps; ++j) {
      const std::vector<uint32_t> c = systematicCounts(kEnergies, slots, (j + 0.5) / steps);
      for (size_t i = 0; i < c.size(); ++i) mean[i] += c[i];
    }
    for (size_t i = 0; i < kEnergies.size(); ++i) {
      const double expectedEnergy = mean[i] / steps * total / double(slots);
      EXPECT_NEAR(expectedEnergy, kEnergies[i], 2e-4 * total) << "member " << i << ", " << slots << " slots";
    }
  }
}

// Survival probability proportional to energy for members below the mean per slot; members
// above it are split (at least floor(w slots / total) copies).
TEST(PmcResampling, SmallMembersSurviveInProportionAndLargeOnesSplit) {
  const double total = std::accumulate(kEnergies.begin(), kEnergies.end(), 0.0);
  const size_t slots = 5;
  int survived = 0;
  const int steps = 100000;
  for (int j = 0; j < steps; ++j) {
    const std::vector<uint32_t> c = systematicCounts(kEnergies, slots, (j + 0.5) / steps);
    survived += c[4] > 0;  // 0.4 of 13.75: survives with probability 0.4 * 5 / 13.75
    EXPECT_GE(c[3], uint32_t(std::floor(7.0 * slots / total)));
    EXPECT_LE(c[3], uint32_t(std::ceil(7.0 * slots / total)));
  }
  EXPECT_NEAR(double(survived) / steps, 0.4 * slots / total, 1e-3);
}

TEST(PmcResampling, NothingToResample) {
  EXPECT_EQ(systematicCounts({0.0, 0.0}, 4, 0.5), (std::vector<uint32_t>{0, 0}));
  EXPECT_TRUE(systematicCounts({}, 4, 0.5).empty());
  EXPECT_EQ(systematicCounts({1.0, 0.0, 0.0}, 3, 0.99), (std::vector<uint32_t>{3, 0, 0}));
}

}  // namespace
}  // namespace erpt
