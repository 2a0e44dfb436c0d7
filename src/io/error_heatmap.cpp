#include "io/error_heatmap.h"

#include <algorithm>
#include <cmath>

#include "erpt/error.h"

namespace erpt {

Rgb8 heatColor(double t) {
  // Control points of a perceptually ordered dark-to-bright map.
  static constexpr double kStops[][3] = {{0, 0, 4}, {87, 16, 110}, {188, 55, 84}, {249, 142, 9}, {252, 255, 164}};
  t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0) * 4;
  const int i = std::min(3, int(t));
  const double f = t - i;
  auto mix = [&](int c) { return uint8_t(std::lround(kStops[i][c] + f * (kStops[i + 1][c] - kStops[i][c]))); };
  return {mix(0), mix(1), mix(2)};
}

Rgb8 Rgb8Image::at(int x, int y) const {
  const size_t i = 3 * (size_t(y) * size_t(width) + size_t(x));
  return {rgb[i], rgb[i + 1], rgb[i + 2]};
}

Rgb8Image errorHeatmap(const RgbImage& image, const RgbImage& reference) {
  if (image.width != reference.width || image.height != reference.height)
    throw UsageError("heat map: the image and the reference differ in size");
  const int k = std::max(1, (256 + image.width - 1) / image.width);
  const int w = image.width * k, h = image.height * k, bar = 22;
  Rgb8Image out{w, h + bar, std::vector<uint8_t>(size_t(w) * size_t(h + bar) * 3, 255)};
  auto fill = [&](int x0, int y0, int x1, int y1, Rgb8 c) {
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        uint8_t* p = &out.rgb[3 * (size_t(y) * size_t(w) + size_t(x))];
        p[0] = c.r, p[1] = c.g, p[2] = c.b;
      }
  };
  const double logLo = std::log10(kHeatmapLow), logHi = std::log10(kHeatmapHigh);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const Color a = image.at(x, y), r = reference.at(x, y);
      Rgb8 color{0, 255, 255};
      if (isFinite(a)) {
        double e = 0;
        for (int ch = 0; ch < 3; ++ch) e += double(a[ch] - r[ch]) * double(a[ch] - r[ch]) / (double(r[ch]) * r[ch] + 0.01);
        e /= 3;
        color = heatColor(e > 0 ? (std::log10(e) - logLo) / (logHi - logLo) : 0.0);
      }
      fill(x * k, y * k, x * k + k - 1, y * k + k - 1, color);
    }
  // The colour scale, kHeatmapLow at the left to kHeatmapHigh at the right (the CLI prints the range).
  const int bx0 = 8, bx1 = w - 9, by = h + 6;
  for (int x = bx0; x <= bx1; ++x) fill(x, by, x, by + 10, heatColor(double(x - bx0) / std::max(1, bx1 - bx0)));
  return out;
}

}  // namespace erpt
