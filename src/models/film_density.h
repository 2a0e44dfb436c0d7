// Where the path tracer puts its film samples, and how ERPT spreads a deposit over pixels.
//
// The path tracer samples each pixel's film positions from the normalized pixel filter h, so
// seeds land at film position x with density H(x) = sum over image pixels j of h(x - c_j).
// ERPT's chains must keep the distribution the seeds start from (ERPT-NOTES, "Pixel
// filters"), so H enters the chain's target (density rule 1) and a deposit at x goes to pixel
// j with weight h(x - c_j) / H(x). In expectation pixel j then receives the integral of
// h(x - c_j) L(x): the filtered image the path tracer estimates. Inside the image H = 1 for
// box and tent; it falls off within a filter radius of the border.
//
// Seeds from BDPT (`--seeds bdpt`) have another film density: camera samples uniform in their
// pixel and light tracing wherever it lands, both inside the image, so H = 1 there (0 outside),
// and a deposit at x goes to pixel j with weight h(x - c_j) / C_j, C_j the part of pixel j's
// normalized filter inside the image: what BDPT's own film (unbiased splatting) estimates.
#pragma once

#include <cstdint>
#include <vector>

#include "models/pixel_filter.h"

namespace erpt {

class FilmDensity {
 public:
  // uniformSeeds: the seeds' film positions are uniform over the image (BDPT seeds).
  FilmDensity(const PixelFilter& filter, int width, int height, bool uniformSeeds = false);
  // H(x, y); 0 outside the region the path tracer samples.
  float density(float x, float y) const {
    if (uniform_) return x >= 0 && x < float(width_) && y >= 0 && y < float(height_) ? 1.0f : 0.0f;
    return axis(x, width_) * axis(y, height_);
  }
  // Calls add(pixel, weight) for every image pixel the deposit at (x, y) reaches; the
  // weights sum to 1 wherever density(x, y) > 0 (for uniform seeds: to 1 where the filter's
  // reach lies inside the image).
  template <class Add>
  void splat(float x, float y, Add&& add) const;
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  // Sum over pixels along one axis of the normalized 1D filter. Box and tent filters at unit
  // spacing sum to exactly 1 where every pixel in reach exists: that test is inline, since
  // every proposal asks it.
  float axis(float x, int size) const {
    const float r = filter_.radius();
    if (filter_.kind() != FilterKind::Gaussian && x >= r && x <= float(size) - r) return 1.0f;
    return axisNearEdges(x, size);
  }
  float axisNearEdges(float x, int size) const;
  const PixelFilter& filter_;
  int width_, height_;
  float norm_;  // 1 / integral of the 1D filter
  bool uniform_;
  std::vector<float> insideX_, insideY_;  // uniform seeds: C per column and row
};

template <class Add>
void FilmDensity::splat(float x, float y, Add&& add) const {
  const float r = filter_.radius();
  int x0 = std::max(0, int(std::floor(x - 0.5f - r)) + 1), x1 = std::min(width_ - 1, int(std::floor(x - 0.5f + r)));
  int y0 = std::max(0, int(std::floor(y - 0.5f - r)) + 1), y1 = std::min(height_ - 1, int(std::floor(y - 0.5f + r)));
  if (x0 > x1 || y0 > y1) return;
  float wx[8], wy[8];
  float sx = 0, sy = 0;
  const int nx = std::min(8, x1 - x0 + 1), ny = std::min(8, y1 - y0 + 1);
  for (int i = 0; i < nx; ++i) sx += wx[i] = filter_.eval(x - (float(x0 + i) + 0.5f));
  for (int i = 0; i < ny; ++i) sy += wy[i] = filter_.eval(y - (float(y0 + i) + 0.5f));
  if (!(sx > 0) || !(sy > 0)) return;
  if (uniform_) {
    for (int i = 0; i < nx; ++i) wx[i] *= norm_ / insideX_[size_t(x0 + i)];
    for (int j = 0; j < ny; ++j) wy[j] *= norm_ / insideY_[size_t(y0 + j)];
    sx = sy = 1;
  }
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      if (wx[i] > 0 && wy[j] > 0) add(uint32_t(y0 + j) * uint32_t(width_) + uint32_t(x0 + i), wx[i] * wy[j] / (sx * sy));
}

}  // namespace erpt
