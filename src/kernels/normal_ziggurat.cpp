#include "kernels/normal_ziggurat.h"

#include <cmath>

#include "core/rng.h"

namespace erpt {

namespace {

constexpr int kLayers = 128;
// The base layer's right edge r and the area v of every layer (the tail's included).
constexpr double kTailStart = 3.442619855899, kLayerArea = 9.91256303526217e-3;
constexpr double kMagnitudeScale = 0x1p-31;  // 31-bit magnitudes

double density(double x) { return std::exp(-0.5 * x * x); }

// Layer i spans [0, x[i]) at heights between f(x[i]) and f(x[i - 1]); accept[i] is the
// magnitude (in 31-bit units) below which a draw lies inside the layer below it, so it needs no
// density test.
struct Ziggurat {
  uint32_t accept[kLayers];
  double width[kLayers];   // x per magnitude unit
  double height[kLayers];  // f(x[i])
  Ziggurat() {
    const double m = 0x1p31;
    double edge = kTailStart, previous = kTailStart;
    const double q = kLayerArea / density(edge);
    accept[0] = uint32_t(edge / q * m);
    accept[1] = 0;
    width[0] = q / m;
    width[kLayers - 1] = edge / m;
    height[0] = 1.0;
    height[kLayers - 1] = density(edge);
    for (int i = kLayers - 2; i >= 1; --i) {
      edge = std::sqrt(-2.0 * std::log(kLayerArea / edge + density(edge)));
      accept[i + 1] = uint32_t(edge / previous * m);
      previous = edge;
      height[i] = density(edge);
      width[i] = edge / m;
    }
  }
};

const Ziggurat& table() {
  static const Ziggurat z;
  return z;
}

}  // namespace

double standardNormalFromBits(uint64_t bits) {
  const Ziggurat& z = table();
  const double sign = (bits >> 63) ? -1.0 : 1.0;
  uint32_t magnitude = uint32_t(bits & 0x7fffffffu);
  int layer = int((bits >> 32) & (kLayers - 1));
  // More numbers, when needed, from a stream keyed by the bits.
  uint32_t next = 0;
  const auto uniform = [&] { return doubleFromBits(uniformBits(bits, next++)); };
  for (;;) {
    if (magnitude < z.accept[layer]) return sign * double(magnitude) * z.width[layer];
    const double x = double(magnitude) * z.width[layer];
    if (layer == 0) {
      // The tail beyond r (Marsaglia's method): x = -log(u1) / r, accepted when
      // -2 log(u2) > x^2.
      for (;;) {
        const double t = -std::log1p(-uniform()) / kTailStart, y = -std::log1p(-uniform());
        if (y + y > t * t) return sign * (kTailStart + t);
      }
    }
    if (z.height[layer] + uniform() * (z.height[layer - 1] - z.height[layer]) < density(x)) return sign * x;
    const uint64_t more = uniformBits(bits, next++);
    magnitude = uint32_t(more & 0x7fffffffu);
    layer = int((more >> 32) & (kLayers - 1));
  }
}

}  // namespace erpt
