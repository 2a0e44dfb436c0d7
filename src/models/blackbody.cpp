#include "models/blackbody.h"

#include <algorithm>
#include <cmath>

#include "cie1931_table.h"

namespace erpt {

double planckRadiance(double nm, double kelvin) {
  // CODATA 2010, the values Mitsuba 0.6 uses.
  constexpr double c = 299792458;       // speed of light, m/s
  constexpr double h = 6.62606957e-34;  // Planck, J s
  constexpr double k = 1.3806488e-23;   // Boltzmann, J/K
  const double metres = nm * 1e-9;
  // Per metre of wavelength; 1e-9 of it per nanometre.
  return 2 * h * c * c / std::pow(metres, 5) / std::expm1(h * c / (k * metres * kelvin)) * 1e-9;
}

Color blackbodyLinearRgb(double kelvin) {
  // Mitsuba integrates the spectrum times the linearly interpolated matching functions
  // (adaptively, to about 1e-5): here each 5 nm row interval by 3-point Gauss-Legendre, exact
  // for the linear table times any quintic, and Planck's law is far smoother than that there.
  const double nodes[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)}, weights[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  double X = 0, Y = 0, Z = 0, yIntegral = 0;
  for (int i = 0; i + 1 < kCie1931Rows; ++i) {
    const Cie1931Sample& a = kCie1931[i];
    const Cie1931Sample& b = kCie1931[i + 1];
    const double start = kCie1931First + i * kCie1931Step, half = 0.5 * kCie1931Step;
    for (int q = 0; q < 3; ++q) {
      const double t = 0.5 * (1 + nodes[q]);  // position in the interval, 0..1
      const double w = weights[q] * half * planckRadiance(start + t * kCie1931Step, kelvin);
      X += w * (a.x + t * (b.x - a.x));
      Y += w * (a.y + t * (b.y - a.y));
      Z += w * (a.z + t * (b.z - a.z));
    }
    yIntegral += half * (a.y + b.y);
  }
  X /= yIntegral;
  Y /= yIntegral;
  Z /= yIntegral;
  // XYZ to linear Rec. 709 RGB, with the matrix's digits as Mitsuba 0.6 writes them.
  const double r = 3.240479 * X - 1.537150 * Y - 0.498535 * Z;
  const double g = -0.969256 * X + 1.875991 * Y + 0.041556 * Z;
  const double bl = 0.055648 * X - 0.204043 * Y + 1.057311 * Z;
  return {float(std::max(0.0, r)), float(std::max(0.0, g)), float(std::max(0.0, bl))};
}

}  // namespace erpt
