// Pixel reconstruction filters with Mitsuba's shapes: box (radius 0.5 px), tent (radius
// 1 px) and gaussian (stddev 0.5 px, truncated at 2 px and shifted to reach 0 there).
// Filters are separable. The path tracer importance-samples sample offsets from the filter
// (each sample then counts fully in its own pixel); ERPT will splat with eval() weights.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "erpt/scene.h"

namespace erpt {

class PixelFilter {
 public:
  explicit PixelFilter(FilterKind kind);
  FilterKind kind() const { return kind_; }
  float radius() const { return radius_; }
  // 1D filter value (unnormalized) at offset x from the pixel centre. (Box and tent inline:
  // ERPT's deposits evaluate them for every pixel they reach.)
  float eval(float x) const {
    x = std::abs(x);
    if (kind_ == FilterKind::Box) return x <= 0.5f ? 1.0f : 0.0f;
    if (kind_ == FilterKind::Tent) return std::max(0.0f, 1.0f - x);
    return evalGaussian(x);
  }
  // Offset from the pixel centre distributed as the normalized 1D filter.
  float sampleOffset(float u) const;

 private:
  float evalGaussian(float x) const;  // at |offset| x
  FilterKind kind_;
  float radius_;
  std::vector<float> cdf_;  // gaussian: tabulated CDF over [-radius, radius]
};

}  // namespace erpt
