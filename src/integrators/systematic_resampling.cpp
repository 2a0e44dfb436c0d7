#include "integrators/systematic_resampling.h"

#include <algorithm>
#include <cmath>

namespace erpt {

std::vector<uint32_t> systematicCounts(const std::vector<double>& weights, size_t slots, double u) {
  std::vector<uint32_t> counts(weights.size(), 0);
  double total = 0;
  for (double w : weights) total += w;
  if (!(total > 0) || slots == 0 || weights.empty()) return counts;
  // Teeth at (j + u) W / slots, j = 0 .. slots - 1. Teeth below x: ceil(x slots / W - u)
  // (clamped); item i owns [C_i, C_i + w_i) of the cumulative weights and gets its teeth.
  const double scale = double(slots) / total;
  auto teethBelow = [&](double x) { return std::clamp(std::ceil(x * scale - u), 0.0, double(slots)); };
  size_t last = weights.size() - 1;
  while (!(weights[last] > 0)) --last;
  double cumulative = 0, before = 0;
  for (size_t i = 0; i <= last; ++i) {
    cumulative += weights[i];
    // The last item of positive weight ends at W exactly (all teeth), whatever the rounding.
    const double after = i == last ? double(slots) : teethBelow(cumulative);
    counts[i] = uint32_t(std::max(0.0, after - before));
    before = std::max(before, after);
  }
  return counts;
}

std::vector<size_t> systematicPicks(const std::vector<double>& weights, size_t slots, double u) {
  const std::vector<uint32_t> counts = systematicCounts(weights, slots, u);
  std::vector<size_t> picks;
  picks.reserve(slots);
  for (size_t i = 0; i < counts.size(); ++i) picks.insert(picks.end(), counts[i], i);
  return picks;
}

}  // namespace erpt
