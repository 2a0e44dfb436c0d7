// The false-colour map of per-pixel error that `erpt diff --heatmap` and `erpt compare` write
// (the convergence plots are drawn by Python: python/erpt/plot.py).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "erpt/image_io.h"

namespace erpt {

// Heat map range: per-pixel relative squared error, mean over channels of
// (x - r)^2 / (r^2 + 0.01) (the pixel's share of relMSE), on a log scale. Fixed, so that maps
// of different images can be compared side by side.
constexpr double kHeatmapLow = 1e-5, kHeatmapHigh = 1.0;

struct Rgb8 {
  uint8_t r, g, b;
};
// The colour of a value in [0, 1] (dark purple - red - yellow).
Rgb8 heatColor(double t);

// 8-bit pixels as they are, rows top to bottom.
struct Rgb8Image {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;
  Rgb8 at(int x, int y) const;
  void writePng(const std::string& path) const { writeRgb8Atomic(path, width, height, rgb.data()); }
};

// The heat map of `image` against `reference` (same size), magnified to at least 256 pixels
// wide, with a bar of the colour scale (low to high, left to right) under it. Non-finite
// pixels are cyan.
Rgb8Image errorHeatmap(const RgbImage& image, const RgbImage& reference);

}  // namespace erpt
