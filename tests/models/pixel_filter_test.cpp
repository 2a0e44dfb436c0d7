// Pixel filter tests: sampleOffset() inverts the CDF of the normalized eval(), so offsets
// drawn from a fine uniform grid of u reproduce the filter's distribution, and stay within
// the filter's radius.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <ostream>
#include <string>
#include <vector>

#include "models/pixel_filter.h"

namespace erpt {
namespace {

struct FilterCase {
  const char* name;
  FilterKind kind;
  float radius;  // Mitsuba's radii: box 0.5, tent 1, gaussian 4 stddev = 2
};

void PrintTo(const FilterCase& c, std::ostream* os) { *os << c.name; }

class PixelFilterTest : public ::testing::TestWithParam<FilterCase> {};

TEST_P(PixelFilterTest, HasMitsubasRadius) {
  PixelFilter f(GetParam().kind);
  EXPECT_EQ(f.kind(), GetParam().kind);
  EXPECT_FLOAT_EQ(f.radius(), GetParam().radius);
  // The filter has no support beyond its radius, and is positive at the centre.
  EXPECT_GT(f.eval(0.0f), 0.0f);
  EXPECT_EQ(f.eval(f.radius() * 1.01f), 0.0f);
  EXPECT_EQ(f.eval(-f.radius() * 1.01f), 0.0f);
}

TEST_P(PixelFilterTest, OffsetsStayWithinRadiusAndAreMonotonic) {
  PixelFilter f(GetParam().kind);
  const float r = f.radius();
  // Include the extreme inputs a [0, 1) generator can produce.
  std::vector<float> us = {0.0f, std::nextafter(1.0f, 0.0f)};
  for (int i = 0; i <= 100000; ++i) us.push_back(std::min(i / 100000.0f, std::nextafter(1.0f, 0.0f)));
  std::sort(us.begin(), us.end());
  float previous = -r;
  for (float u : us) {
    float x = f.sampleOffset(u);
    ASSERT_TRUE(std::isfinite(x)) << "u = " << u;
    ASSERT_GE(x, -r) << "u = " << u;
    ASSERT_LE(x, r) << "u = " << u;
    // An inverse CDF is non-decreasing; stratified u then stay stratified in x.
    ASSERT_GE(x, previous) << "u = " << u;
    previous = x;
  }
}

TEST_P(PixelFilterTest, SampledOffsetsFollowNormalizedFilter) {
  PixelFilter f(GetParam().kind);
  const double r = f.radius();

  // Reference CDF of eval() normalized over [-r, r]: midpoint rule in double with
  // `perCheck` cells between consecutive check points.
  const int checks = 2000, perCheck = 100;
  const double h = 2 * r / (double(checks) * perCheck);
  std::vector<double> cdf(checks + 1, 0.0);
  for (int j = 0; j < checks; ++j) {
    double sum = 0;
    for (int k = 0; k < perCheck; ++k) sum += f.eval(float(-r + ((double(j) * perCheck + k) + 0.5) * h));
    cdf[j + 1] = cdf[j] + sum * h;
  }
  const double total = cdf.back();
  ASSERT_GT(total, 0);
  for (double& c : cdf) c /= total;

  // Offsets from a fine uniform grid of u: their empirical CDF equals the inverse-CDF
  // sampler's target up to the grid's resolution 1/n.
  const int n = 1 << 20;
  std::vector<float> offsets(n);
  for (int i = 0; i < n; ++i) offsets[i] = f.sampleOffset((i + 0.5f) / n);
  std::sort(offsets.begin(), offsets.end());

  double maxDiff = 0, worstX = 0;
  for (int j = 0; j <= checks; ++j) {
    double x = -r + 2 * r * j / checks;
    double empirical = double(std::upper_bound(offsets.begin(), offsets.end(), float(x)) - offsets.begin()) / n;
    double d = std::abs(empirical - cdf[j]);
    if (d > maxDiff) {
      maxDiff = d;
      worstX = x;
    }
  }
  // Exact inversion leaves only grid, float and tabulation errors (about 2e-6 here); the
  // bound is 10x that, tight enough to catch e.g. a one-cell shift of the gaussian's table.
  EXPECT_LT(maxDiff, 2e-5) << GetParam().name << ": largest CDF difference " << maxDiff << " at x = " << worstX;

  // A coarse histogram as well: the density of offsets matches eval() in every bin, which
  // pinpoints where a mismatch is (the CDF difference above is the sharper criterion).
  const int bins = 40;
  std::vector<int> counts(bins, 0);
  for (float x : offsets) counts[std::min(bins - 1, int((x + r) / (2 * r) * bins))]++;
  for (int b = 0; b < bins; ++b) {
    double expected = cdf[(b + 1) * checks / bins] - cdf[b * checks / bins];
    EXPECT_NEAR(double(counts[b]) / n, expected, 4e-5) << GetParam().name << " bin " << b;
  }
}

INSTANTIATE_TEST_SUITE_P(Filters, PixelFilterTest,
                         ::testing::Values(FilterCase{"Box", FilterKind::Box, 0.5f},
                                           FilterCase{"Tent", FilterKind::Tent, 1.0f},
                                           FilterCase{"Gaussian", FilterKind::Gaussian, 2.0f}),
                         [](const ::testing::TestParamInfo<FilterCase>& info) { return info.param.name; });

}  // namespace
}  // namespace erpt
