// The Hosek-Wilkie sky in RGB (Hosek and Wilkie 2012, "An analytic model for full spectral
// sky-dome radiance"), evaluated as Mitsuba 0.6's `sky` emitter does in its RGB build.
#include "models/sky_model.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "hosek_wilkie_rgb_data.h"

namespace erpt {

namespace {

constexpr double kPiD = 3.14159265358979323846;

// The datasets hold, per ground albedo (0 and 1) and integer turbidity (1..10), six control
// points of a quintic Bezier curve over x = (solar elevation / (pi/2))^(1/3), each with
// `count` values (9 distribution parameters, or 1 for the radiance scale). The model's value
// for any turbidity and albedo interpolates both linearly.
void cook(const double* dataset, int count, double turbidity, double albedo, double solarElevation, double* out) {
  const double x = std::cbrt(solarElevation / (kPiD / 2));
  const double bernstein[6] = {std::pow(1 - x, 5),     5 * std::pow(1 - x, 4) * x,   10 * std::pow(1 - x, 3) * x * x,
                               10 * std::pow(1 - x, 2) * x * x * x, 5 * (1 - x) * std::pow(x, 4), std::pow(x, 5)};
  const int low = std::clamp(int(turbidity), 1, 10);
  const double rem = turbidity - low;
  for (int i = 0; i < count; ++i) out[i] = 0;
  auto add = [&](int albedoIndex, int turbidityIndex, double weight) {
    if (weight == 0) return;
    const double* points = dataset + (albedoIndex * 10 + (turbidityIndex - 1)) * 6 * count;
    for (int i = 0; i < count; ++i) {
      double v = 0;
      for (int k = 0; k < 6; ++k) v += bernstein[k] * points[k * count + i];
      out[i] += weight * v;
    }
  };
  add(0, low, (1 - albedo) * (1 - rem));
  add(1, low, albedo * (1 - rem));
  if (low < 10) {
    add(0, low + 1, (1 - albedo) * rem);
    add(1, low + 1, albedo * rem);
  }
}

// Mitsuba 0.6 divides the RGB model by the sum of its CIE Y table (its RGB unit).
constexpr double kMitsubaRgbUnit = 106.856980;

}  // namespace

HosekWilkieSky::HosekWilkieSky(double turbidity, Color albedo, SunAngles sun) : sun_(sun) {
  if (!(turbidity >= 1 && turbidity <= 10))
    throw std::invalid_argument("turbidity must be in [1, 10], got " + std::to_string(turbidity));
  for (int c = 0; c < 3; ++c)
    if (!(albedo[c] >= 0 && albedo[c] <= 1)) throw std::invalid_argument("albedo must be in [0, 1] in every channel");
  const double elevation = kPiD / 2 - sun.zenith;
  if (!(elevation >= 0) || !std::isfinite(sun.azimuth))
    throw std::invalid_argument("the sun is below the horizon: the sky model has no night sky");
  for (int c = 0; c < 3; ++c) {
    cook(kHosekWilkieRgbCoefficients[c], 9, turbidity, albedo[c], elevation, config_[c]);
    cook(kHosekWilkieRgbRadiance[c], 1, turbidity, albedo[c], elevation, &scale_[c]);
  }
}

double HosekWilkieSky::modelRadiance(int channel, double theta, double gamma) const {
  const double* p = config_[channel];
  const double cosGamma = std::cos(gamma), cosTheta = std::cos(theta);
  // (1 + A e^(B / (cos theta + 0.01))) (C + D e^(E gamma) + F cos^2 gamma + G chi(H, gamma) + I sqrt(cos theta)),
  // the parameters stored in the order A B C D E F G I H.
  const double mie = (1 + cosGamma * cosGamma) / std::pow(1 + p[8] * p[8] - 2 * p[8] * cosGamma, 1.5);
  const double f = (1 + p[0] * std::exp(p[1] / (cosTheta + 0.01))) *
                   (p[2] + p[3] * std::exp(p[4] * gamma) + p[5] * cosGamma * cosGamma + p[6] * mie + p[7] * std::sqrt(cosTheta));
  return f * scale_[channel];
}

Color HosekWilkieSky::radiance(double theta, double phi) const {
  if (std::cos(theta) <= 0) return Color(0.0f);
  const double cosGamma = std::cos(theta) * std::cos(sun_.zenith) +
                          std::sin(theta) * std::sin(sun_.zenith) * std::cos(phi - sun_.azimuth);
  const double gamma = std::acos(std::clamp(cosGamma, -1.0, 1.0));
  Color out;
  for (int c = 0; c < 3; ++c) out[c] = float(std::max(0.0, modelRadiance(c, theta, gamma) / kMitsubaRgbUnit));
  return out;
}

void checkSkySettings(const SkySettings& s) {
  if (!(s.stretch >= 1 && s.stretch <= 2)) throw std::invalid_argument("stretch must be in [1, 2]");
  if (s.resolution < 2 || s.resolution > 8192) throw std::invalid_argument("resolution must be in [2, 8192]");
  if (!(s.scale >= 0) || !std::isfinite(s.scale)) throw std::invalid_argument("scale must be a finite number >= 0");
  HosekWilkieSky(s.turbidity, s.albedo, s.sun);  // turbidity, albedo and the sun's height
}

RgbImage rasterizeSky(const SkySettings& s) {
  checkSkySettings(s);
  const HosekWilkieSky sky(s.turbidity, s.albedo, s.sun);
  RgbImage image;
  image.width = s.resolution;
  image.height = s.resolution / 2;
  image.pixels.resize(size_t(image.width) * image.height);
  for (int y = 0; y < image.height; ++y) {
    const double zenith = (y + 0.5) * kPiD / image.height;
    double theta = zenith / s.stretch, fade = 1;
    if (s.extend) {
      // Mitsuba 0.6's "extend": below the horizon, the horizon's radiance; everything fades
      // with a smooth step from the horizon to the nadir.
      const double t = std::clamp(2 - 2 * zenith / kPiD, 0.0, 1.0);
      fade = t * t * (3 - 2 * t);
      if (std::cos(theta) <= 0) theta = kPiD / 2 - 1e-4;
    }
    for (int x = 0; x < image.width; ++x) {
      const double phi = (x + 0.5) * 2 * kPiD / image.width;
      image.at(x, y) = sky.radiance(theta, phi) * float(fade * s.scale);
    }
  }
  return image;
}

}  // namespace erpt
