#include "models/spectrum.h"

#include <cmath>

namespace erpt {

namespace {

// Piecewise Gaussian lobes of the analytic CIE 1931 fit by Wyman, Sloan and Shirley (2013).
double lobe(double x, double mu, double s1, double s2) {
  double t = (x - mu) / (x < mu ? s1 : s2);
  return std::exp(-0.5 * t * t);
}
double xBar(double w) {
  return 1.056 * lobe(w, 599.8, 37.9, 31.0) + 0.362 * lobe(w, 442.0, 16.0, 26.7) - 0.065 * lobe(w, 501.1, 20.4, 26.2);
}
double yBar(double w) { return 0.821 * lobe(w, 568.8, 46.9, 40.5) + 0.286 * lobe(w, 530.9, 16.3, 31.1); }
double zBar(double w) { return 1.217 * lobe(w, 437.0, 11.8, 36.0) + 0.681 * lobe(w, 459.0, 26.0, 13.8); }

Color xyzToLinearSrgb(double X, double Y, double Z) {
  return {float(3.2404542 * X - 1.5371385 * Y - 0.4985314 * Z), float(-0.9692660 * X + 1.8760108 * Y + 0.0415560 * Z),
          float(0.0556434 * X - 0.2040259 * Y + 1.0572252 * Z)};
}

}  // namespace

Color spectrumToLinearRgb(const std::function<double(double)>& radiance) {
  double X = 0, Y = 0, Z = 0, yIntegral = 0;
  for (double w = 360; w <= 830; w += 1) {
    const double v = radiance(w);
    X += v * xBar(w);
    Y += v * yBar(w);
    Z += v * zBar(w);
    yIntegral += yBar(w);
  }
  return xyzToLinearSrgb(X / yIntegral, Y / yIntegral, Z / yIntegral);
}

}  // namespace erpt
