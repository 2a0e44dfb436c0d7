#include "io/error_plots.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "erpt/error.h"

namespace erpt {

namespace {

constexpr Rgb8 kWhite{255, 255, 255}, kBlack{0, 0, 0}, kGrid{225, 225, 225}, kMinorGrid{242, 242, 242},
    kAxisText{60, 60, 60}, kGuide{150, 150, 150};
constexpr Rgb8 kSeriesColors[] = {{31, 119, 180}, {255, 127, 14}, {44, 160, 44}, {214, 39, 40}, {148, 103, 189},
                                  {140, 86, 75}};

// "0.01" .. "1000" as plain numbers, other decades as "1E-5".
std::string decadeLabel(int k) {
  if (k >= -2 && k <= 4) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.*f", k < 0 ? -k : 0, std::pow(10.0, k));
    return buf;
  }
  return "1E" + std::to_string(k);
}

struct LogAxis {
  int lo = 0, hi = 1;  // decades
  void fit(const std::vector<double>& values) {
    double mn = HUGE_VAL, mx = -HUGE_VAL;
    for (double v : values)
      if (v > 0 && std::isfinite(v)) mn = std::min(mn, v), mx = std::max(mx, v);
    if (!(mn <= mx)) return;
    lo = int(std::floor(std::log10(mn)));
    hi = int(std::ceil(std::log10(mx)));
    if (hi <= lo) hi = lo + 1;
  }
  double fraction(double v) const { return (std::log10(v) - lo) / double(hi - lo); }
};

struct Panel {
  int x0, y0, x1, y1;  // plot area in canvas pixels
  LogAxis x, y;
  double px(double v) const { return x0 + x.fraction(v) * (x1 - x0); }
  double py(double v) const { return y1 - y.fraction(v) * (y1 - y0); }
};

void drawPanel(Canvas& c, const Panel& p, const std::vector<ErrorSeries>& series, bool relative,
               const std::string& ylabel) {
  // Grid: decades and their 2..9 multiples.
  for (int k = p.x.lo; k < p.x.hi; ++k)
    for (int m = 2; m <= 9; ++m) c.line(p.px(m * std::pow(10.0, k)), p.y0, p.px(m * std::pow(10.0, k)), p.y1, kMinorGrid);
  for (int k = p.y.lo; k < p.y.hi; ++k)
    for (int m = 2; m <= 9; ++m) c.line(p.x0, p.py(m * std::pow(10.0, k)), p.x1, p.py(m * std::pow(10.0, k)), kMinorGrid);
  for (int k = p.x.lo; k <= p.x.hi; ++k) {
    const double x = p.px(std::pow(10.0, k));
    c.line(x, p.y0, x, p.y1, kGrid);
    const std::string label = decadeLabel(k);
    c.text(int(x) - Canvas::textWidth(label) / 2, p.y1 + 6, label, kAxisText);
  }
  for (int k = p.y.lo; k <= p.y.hi; ++k) {
    const double y = p.py(std::pow(10.0, k));
    c.line(p.x0, y, p.x1, y, kGrid);
    const std::string label = decadeLabel(k);
    c.text(p.x0 - 6 - Canvas::textWidth(label), int(y) - 3, label, kAxisText);
  }
  // Slope -1 through the first series' last point: where constant efficiency would go.
  if (!series.empty() && !series[0].seconds.empty()) {
    const double t = series[0].seconds.back(), e = relative ? series[0].relMse.back() : series[0].mse.back();
    if (t > 0 && e > 0) {
      const double ta = std::pow(10.0, p.x.lo), tb = std::pow(10.0, p.x.hi);
      double xa = p.px(ta), ya = p.py(e * t / ta), xb = p.px(tb), yb = p.py(e * t / tb);
      // Clip to the panel in y (the line is straight in log-log space).
      auto clipY = [&](double& xs, double& ys, double xo, double yo) {
        const double target = ys < p.y0 ? p.y0 : ys > p.y1 ? p.y1 : ys;
        if (target != ys) xs = xs + (target - ys) * (xo - xs) / (yo - ys), ys = target;
      };
      clipY(xa, ya, xb, yb);
      clipY(xb, yb, xa, ya);
      c.line(xa, ya, xb, yb, kGuide, 1, 6);
    }
  }
  for (size_t s = 0; s < series.size(); ++s) {
    const Rgb8 color = kSeriesColors[s % std::size(kSeriesColors)];
    const std::vector<double>& e = relative ? series[s].relMse : series[s].mse;
    bool havePrevious = false;
    double lx = 0, ly = 0;
    for (size_t i = 0; i < series[s].seconds.size(); ++i) {
      if (!(series[s].seconds[i] > 0) || !(e[i] > 0)) continue;
      const double x = p.px(series[s].seconds[i]), y = p.py(e[i]);
      if (havePrevious) c.line(lx, ly, x, y, color, 2);
      c.fillRect(int(x) - 3, int(y) - 3, int(x) + 3, int(y) + 3, color);
      lx = x, ly = y, havePrevious = true;
    }
  }
  // Frame and labels.
  c.line(p.x0, p.y0, p.x1, p.y0, kBlack);
  c.line(p.x0, p.y1, p.x1, p.y1, kBlack);
  c.line(p.x0, p.y0, p.x0, p.y1, kBlack);
  c.line(p.x1, p.y0, p.x1, p.y1, kBlack);
  c.text(p.x0, p.y0 - 16, ylabel, kBlack, 1);
  const std::string xlabel = "RENDER TIME (S)";
  c.text((p.x0 + p.x1) / 2 - Canvas::textWidth(xlabel) / 2, p.y1 + 22, xlabel, kBlack);
  // Legend, top right inside the panel.
  int ly = p.y0 + 8;
  for (size_t s = 0; s <= series.size(); ++s) {
    const bool guide = s == series.size();
    const std::string name = guide ? "SLOPE -1" : series[s].name;
    const int lx = p.x1 - 12 - Canvas::textWidth(name) - 24;
    c.fillRect(lx - 4, ly - 4, p.x1 - 6, ly + 11, kWhite);
    if (guide)
      c.line(lx, ly + 3, lx + 16, ly + 3, kGuide, 1, 3);
    else
      c.fillRect(lx, ly + 1, lx + 16, ly + 5, kSeriesColors[s % std::size(kSeriesColors)]);
    c.text(lx + 24, ly, name, kBlack);
    ly += 14;
  }
}

}  // namespace

Rgb8 heatColor(double t) {
  // Control points of a perceptually ordered dark-to-bright map.
  static constexpr double kStops[][3] = {{0, 0, 4}, {87, 16, 110}, {188, 55, 84}, {249, 142, 9}, {252, 255, 164}};
  t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0) * 4;
  const int i = std::min(3, int(t));
  const double f = t - i;
  auto mix = [&](int c) { return uint8_t(std::lround(kStops[i][c] + f * (kStops[i + 1][c] - kStops[i][c]))); };
  return {mix(0), mix(1), mix(2)};
}

Canvas errorHeatmap(const RgbImage& image, const RgbImage& reference) {
  if (image.width != reference.width || image.height != reference.height)
    throw UsageError("heat map: the image and the reference differ in size");
  const int k = std::max(1, (256 + image.width - 1) / image.width);
  const int w = image.width * k, h = image.height * k, bar = 44;
  Canvas c(w, h + bar, kWhite);
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
      c.fillRect(x * k, y * k, x * k + k - 1, y * k + k - 1, color);
    }
  // Colour bar with its range.
  const int bx0 = 8, bx1 = w - 9, by = h + 6;
  for (int x = bx0; x <= bx1; ++x) c.fillRect(x, by, x, by + 10, heatColor(double(x - bx0) / (bx1 - bx0)));
  const std::string lo = decadeLabel(int(logLo)), hi = decadeLabel(int(logHi)), label = "REL. SQ. ERROR";
  c.text(bx0, by + 16, lo, kBlack);
  c.text(bx1 + 1 - Canvas::textWidth(hi), by + 16, hi, kBlack);
  if (Canvas::textWidth(label) + Canvas::textWidth(lo) + Canvas::textWidth(hi) + 24 < w)
    c.text(w / 2 - Canvas::textWidth(label) / 2, by + 16, label, kBlack);
  return c;
}

Canvas errorVsTimePlot(const std::vector<ErrorSeries>& series, const std::string& title) {
  Canvas c(1040, 470, kWhite);
  std::vector<double> seconds, mse, rel;
  for (const ErrorSeries& s : series) {
    seconds.insert(seconds.end(), s.seconds.begin(), s.seconds.end());
    mse.insert(mse.end(), s.mse.begin(), s.mse.end());
    rel.insert(rel.end(), s.relMse.begin(), s.relMse.end());
  }
  Panel left{70, 60, 500, 400, {}, {}}, right{610, 60, 1020, 400, {}, {}};
  left.x.fit(seconds);
  right.x = left.x;
  left.y.fit(mse);
  right.y.fit(rel);
  c.text(20, 14, title, kBlack, 2);
  drawPanel(c, left, series, false, "MSE");
  drawPanel(c, right, series, true, "RELATIVE MSE");
  return c;
}

}  // namespace erpt
