#include "models/pixel_filter.h"

#include <algorithm>

#include "core/cdf_search.h"

namespace erpt {

namespace {
constexpr float kGaussianStddev = 0.5f;
constexpr int kCdfSize = 4096;
}  // namespace

PixelFilter::PixelFilter(FilterKind kind) : kind_(kind) {
  radius_ = kind == FilterKind::Box ? 0.5f : kind == FilterKind::Tent ? 1.0f : 4 * kGaussianStddev;
  if (kind == FilterKind::Gaussian) {
    // Midpoint-rule CDF; sampleOffset() inverts it with linear interpolation.
    cdf_.resize(kCdfSize + 1);
    cdf_[0] = 0;
    for (int i = 0; i < kCdfSize; ++i) {
      float x = -radius_ + 2 * radius_ * (i + 0.5f) / kCdfSize;
      cdf_[i + 1] = cdf_[i] + eval(x);
    }
    for (float& c : cdf_) c /= cdf_.back();
  }
}

float PixelFilter::evalGaussian(float x) const {
  auto g = [](float t) { return std::exp(-t * t / (2 * kGaussianStddev * kGaussianStddev)); };
  return std::max(0.0f, g(x) - g(radius_));
}

float PixelFilter::sampleOffset(float u) const {
  switch (kind_) {
    case FilterKind::Box:
      return u - 0.5f;
    case FilterKind::Tent:
      return u < 0.5f ? -1.0f + std::sqrt(2 * u) : 1.0f - std::sqrt(2 * (1 - u));
    default: {
      size_t i = upperBoundIndex(cdf_.data(), cdf_.size(), u);
      i = std::clamp<size_t>(i, 1, kCdfSize);
      float c0 = cdf_[i - 1], c1 = cdf_[i];
      float t = c1 > c0 ? (u - c0) / (c1 - c0) : 0.5f;
      return -radius_ + 2 * radius_ * (float(i - 1) + t) / kCdfSize;
    }
  }
}

}  // namespace erpt
