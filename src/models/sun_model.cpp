// The sun disk's radiance through the atmosphere (Preetham, Shirley and Smits 1999, "A practical
// analytic model for daylight", appendix: the transmittance model and tables they take from
// Iqbal's "An introduction to solar radiation"), as Mitsuba 0.6 evaluates it, and the disk
// drawn into an environment map.
#include <algorithm>
#include <cmath>
#include <vector>

#include "models/spectrum.h"
#include "models/sun_model.h"

namespace erpt {

namespace {

constexpr double kPiD = 3.14159265358979323846;

// A tabulated spectrum: linear between samples, zero outside them.
struct Table {
  std::vector<double> nm, value;
  double operator()(double w) const {
    if (w < nm.front() || w > nm.back()) return 0;
    size_t i = size_t(std::upper_bound(nm.begin(), nm.end(), w) - nm.begin());
    if (i >= nm.size()) return value.back();
    const double t = (w - nm[i - 1]) / (nm[i] - nm[i - 1]);
    return value[i - 1] * (1 - t) + value[i] * t;
  }
};

// Ozone absorption coefficient (1/cm).
const Table kOzone{{300, 305, 310, 315, 320, 325, 330, 335, 340, 345, 350, 355, 445, 450, 455, 460,
                    465, 470, 475, 480, 485, 490, 495, 500, 505, 510, 515, 520, 525, 530, 535, 540,
                    545, 550, 555, 560, 565, 570, 575, 580, 585, 590, 595, 600, 605, 610, 620, 630,
                    640, 650, 660, 670, 680, 690, 700, 710, 720, 730, 740, 750, 760, 770, 780, 790},
                   {10.0, 4.8,  2.7,  1.35, .8,   .380, .160, .075, .04,  .019, .007, .0,   .003, .003, .004, .006,
                    .008, .009, .012, .014, .017, .021, .025, .03,  .035, .04,  .045, .048, .057, .063, .07,  .075,
                    .08,  .085, .095, .103, .110, .12,  .122, .12,  .118, .115, .12,  .125, .130, .12,  .105, .09,
                    .079, .067, .057, .048, .036, .028, .023, .018, .014, .011, .010, .009, .007, .004, .0,   .0}};
// Mixed-gas absorption coefficient.
const Table kMixedGases{{759, 760, 770, 771}, {0, 3.0, 0.210, 0}};
// Water-vapour absorption coefficient.
const Table kWaterVapour{{689, 690, 700, 710, 720, 730, 740, 750, 760, 770, 780, 790, 800},
                         {0, 0.160e-1, 0.240e-1, 0.125e-1, 0.100e+1, 0.870, 0.610e-1, 0.100e-2, 0.100e-4, 0.100e-4,
                          0.600e-3, 0.175e-1, 0.360e-1}};
// Extraterrestrial solar spectral radiance, W / (m^2 sr nm).
const Table kSolar{{380, 390, 400, 410, 420, 430, 440, 450, 460, 470, 480, 490, 500, 510, 520, 530,
                    540, 550, 560, 570, 580, 590, 600, 610, 620, 630, 640, 650, 660, 670, 680, 690,
                    700, 710, 720, 730, 740, 750},
                   {16559.0, 16233.7, 21127.5, 25888.2, 25829.1, 24232.3, 26760.5, 29658.3, 30545.4, 30057.5,
                    30663.7, 28830.4, 28712.1, 27825.0, 27100.6, 27233.6, 26361.3, 25503.8, 25060.2, 25311.6,
                    25355.9, 25134.2, 24631.5, 24173.2, 23685.3, 23212.1, 22827.7, 22339.8, 21970.2, 21526.7,
                    21097.9, 20728.3, 20240.4, 19870.8, 19427.2, 19072.4, 18628.9, 18259.2}};

}  // namespace

Color sunRadiance(double zenith, double turbidity) {
  const double beta = 0.04608365822050 * turbidity - 0.04586025928522;  // aerosol amount (Angstrom)
  // Relative optical mass (Kasten's formula with the zenith angle in degrees).
  const double m = 1 / (std::cos(zenith) + 0.15 * std::pow(93.885 - zenith * 180 / kPiD, -1.253));
  // The attenuated spectrum at 5 nm steps from 350 to 800 nm, linear in between.
  std::vector<double> samples;
  for (int i = 0; i <= 90; ++i) {
    const double nm = 350 + 5 * i, um = nm / 1000;
    const double rayleigh = std::exp(-m * 0.008735 * std::pow(um, -4.08));
    const double aerosol = std::exp(-m * beta * std::pow(um, -1.3));  // Angstrom's alpha = 1.3
    const double ozone = std::exp(-m * kOzone(nm) * 0.35);           // 0.35 cm of ozone
    const double kg = kMixedGases(nm), kwa = kWaterVapour(nm), water = 2.0;  // 2 cm precipitable water
    const double gases = std::exp(-1.41 * kg * m / std::pow(1 + 118.93 * kg * m, 0.45));
    const double vapour = std::exp(-0.2385 * kwa * water * m / std::pow(1 + 20.07 * kwa * water * m, 0.45));
    samples.push_back(kSolar(nm) * rayleigh * aerosol * ozone * gases * vapour);
  }
  const Color rgb = spectrumToLinearRgb([&](double nm) {
    if (nm < 350 || nm > 800) return 0.0;
    const double x = (nm - 350) / 5;
    const size_t i = std::min(size_t(x), size_t(89));
    const double t = x - double(i);
    return samples[i] * (1 - t) + samples[i + 1] * t;
  });
  return Color(std::max(0.0f, rgb.x), std::max(0.0f, rgb.y), std::max(0.0f, rgb.z));
}

void addSunToImage(RgbImage& image, SunAngles sun, Color radiance, double radiusScale) {
  const int w = image.width, h = image.height;
  const double cosMax = std::cos(kSunAngularRadius * radiusScale);
  const double power = 2 * kPiD * (1 - std::cos(kSunAngularRadius));  // per unit radiance
  // Stratified directions uniform in the widened disk's solid angle: about a thousand per
  // pixel it covers (at least 100, at most four million in all), each carrying an equal share
  // of the power.
  const double covered = double(w) * h * 0.5 * (1 - cosMax);
  const int n = int(std::ceil(std::sqrt(std::clamp(covered * 1000, 100.0, 4e6))));
  const Frame frame(directionOf(sun.zenith, sun.azimuth));
  const Color share = radiance * float(power / (double(n) * n));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double cosTheta = 1 - (i + 0.5) / n * (1 - cosMax), sinTheta = std::sqrt(1 - cosTheta * cosTheta);
      const double phi = 2 * kPiD * (j + 0.5) / n;
      const Vec3 d = frame.toWorld(Vec3{float(sinTheta * std::cos(phi)), float(sinTheta * std::sin(phi)), float(cosTheta)});
      const SunAngles a = anglesOf(normalize(d));
      const int x = std::clamp(int(a.azimuth / (2 * kPiD) * w), 0, w - 1);
      const int y = std::clamp(int(a.zenith / kPiD * h), 0, h - 1);
      const double pixelSolidAngle = 2 * kPiD / w * (std::cos(kPiD * y / h) - std::cos(kPiD * (y + 1) / h));
      image.at(x, y) += share / float(pixelSolidAngle);
    }
}

}  // namespace erpt
