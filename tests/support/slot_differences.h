// How far a vector kernel's results lie from the scalar code's, slot by slot: the largest
// component's difference relative to the scalar value's largest component, and the quantiles
// the kernel tests bound (a rounding difference may be large on a few slots, never on many).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "erpt/math.h"

namespace erpt::test {

// `floor`: the smallest scale a difference is measured against (values near zero).
inline double relativeDifference(Vec3 a, Vec3 b, float floor = 1e-6f) {
  const double scale = std::max({std::abs(b.x), std::abs(b.y), std::abs(b.z), floor});
  return std::max({std::abs(a.x - b.x), std::abs(a.y - b.y), std::abs(a.z - b.z)}) / scale;
}

// The p-quantile (0 <= p <= 1) of `v`, 0 when it is empty.
inline double quantile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[size_t(p * double(v.size() - 1))];
}

}  // namespace erpt::test
