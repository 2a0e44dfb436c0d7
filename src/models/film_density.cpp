#include "models/film_density.h"

#include <algorithm>
#include <cmath>

namespace erpt {

FilmDensity::FilmDensity(const PixelFilter& filter, int width, int height, bool uniformSeeds)
    : filter_(filter), width_(width), height_(height), uniform_(uniformSeeds) {
  // Integral of the 1D filter by the midpoint rule (box and tent: exactly 1).
  const int n = 4096;
  const float r = filter.radius();
  double sum = 0;
  for (int i = 0; i < n; ++i) sum += filter.eval(-r + 2 * r * (i + 0.5f) / n);
  norm_ = float(n / (sum * 2 * r));
  if (!uniform_) return;
  // C per pixel along an axis: the normalized filter's integral over the image's extent.
  auto inside = [&](int size) {
    std::vector<float> c(static_cast<size_t>(size));
    const int m = 256;
    for (int p = 0; p < size; ++p) {
      const double centre = p + 0.5, a = std::max(0.0, centre - r), b = std::min(double(size), centre + r);
      double s = 0;
      for (int i = 0; i < m; ++i) s += filter.eval(float(a + (b - a) * (i + 0.5) / m - centre));
      c[size_t(p)] = float(s * (b - a) / m) * norm_;
    }
    return c;
  };
  insideX_ = inside(width);
  insideY_ = inside(height);
}

float FilmDensity::axisNearEdges(float x, int size) const {
  const float r = filter_.radius();
  int lo = std::max(0, int(std::floor(x - 0.5f - r)) + 1), hi = std::min(size - 1, int(std::floor(x - 0.5f + r)));
  float sum = 0;
  for (int p = lo; p <= hi; ++p) sum += filter_.eval(x - (float(p) + 0.5f));
  return sum * norm_;
}

}  // namespace erpt
