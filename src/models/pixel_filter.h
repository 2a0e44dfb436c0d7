// Pixel reconstruction filters with Mitsuba's shapes: box (radius 0.5 px), tent (radius
// 1 px) and gaussian (stddev 0.5 px, truncated at 2 px and shifted to reach 0 there).
// Filters are separable. The path tracer importance-samples sample offsets from the filter
// (each sample then counts fully in its own pixel); ERPT will splat with eval() weights.
#pragma once

#include <vector>

#include "erpt/scene.h"

namespace erpt {

class PixelFilter {
 public:
  explicit PixelFilter(FilterKind kind);
  FilterKind kind() const { return kind_; }
  float radius() const { return radius_; }
  // 1D filter value (unnormalized) at offset x from the pixel centre.
  float eval(float x) const;
  // Offset from the pixel centre distributed as the normalized 1D filter.
  float sampleOffset(float u) const;

 private:
  FilterKind kind_;
  float radius_;
  std::vector<float> cdf_;  // gaussian: tabulated CDF over [-radius, radius]
};

}  // namespace erpt
