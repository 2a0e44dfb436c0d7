// The pictures `erpt diff --heatmap` and `erpt compare` draw: a false-colour map of per-pixel
// error and log-log plots of error versus render time.
#pragma once

#include <string>
#include <vector>

#include "io/canvas.h"
#include "erpt/image_io.h"

namespace erpt {

// Heat map range: per-pixel relative squared error, mean over channels of
// (x - r)^2 / (r^2 + 0.01) (the pixel's share of relMSE), on a log scale. Fixed, so that maps
// of different images can be compared side by side.
constexpr double kHeatmapLow = 1e-5, kHeatmapHigh = 1.0;

// The heat map of `image` against `reference` (same size), magnified to at least 256 pixels
// wide, with a colour bar and its range under it. Non-finite pixels are cyan.
Canvas errorHeatmap(const RgbImage& image, const RgbImage& reference);
// The colour of a value in [0, 1] (dark purple - red - yellow).
Rgb8 heatColor(double t);

struct ErrorSeries {
  std::string name;                          // legend entry
  std::vector<double> seconds, mse, relMse;  // one point per saved image
};

// Two log-log panels side by side, MSE and relMSE versus seconds, one curve per series, with
// a dashed line of slope -1 (error proportional to 1/time: constant efficiency) for reference.
Canvas errorVsTimePlot(const std::vector<ErrorSeries>& series, const std::string& title);

}  // namespace erpt
