// upperBoundIndex must find exactly what std::upper_bound finds, for every size and for the
// values sampling can meet: each entry itself, its neighbours one ulp away, runs of equal
// entries (zero-probability items), and values outside the range.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "core/cdf_search.h"

namespace erpt {
namespace {

template <class Value>
void expectSameAsUpperBound(const std::vector<float>& cdf, Value u) {
  const size_t expected = size_t(std::upper_bound(cdf.begin(), cdf.end(), u) - cdf.begin());
  EXPECT_EQ(upperBoundIndex(cdf.data(), cdf.size(), u), expected) << "size " << cdf.size() << ", u " << u;
}

TEST(CdfSearch, FindsWhatUpperBoundFinds) {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> weight(0.0f, 1.0f);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (size_t n = 0; n <= 70; ++n) {
    for (int trial = 0; trial < 5; ++trial) {
      std::vector<float> cdf(n);
      float running = 0;
      for (float& c : cdf) {
        running += trial % 2 == 0 && weight(random) < 0.3f ? 0.0f : weight(random);  // some repeats
        c = running;
      }
      if (n > 0 && running > 0)
        for (float& c : cdf) c /= running;
      for (float c : cdf) {
        for (float v : {c, std::nextafter(c, -1.0f), std::nextafter(c, 2.0f)}) {
          expectSameAsUpperBound(cdf, v);
          expectSameAsUpperBound(cdf, double(v));
        }
        // doubles between two neighbouring floats compare differently from either float
        expectSameAsUpperBound(cdf, double(c) + 0x1p-40);
        expectSameAsUpperBound(cdf, double(c) - 0x1p-40);
      }
      for (double u : {-1.0, 0.0, 1.0, 2.0}) expectSameAsUpperBound(cdf, u);
      for (int k = 0; k < 50; ++k) expectSameAsUpperBound(cdf, uniform(random));
    }
  }
}

}  // namespace
}  // namespace erpt
