#include "support/image_stats.h"

#include <stdexcept>

namespace erpt::test {

Color meanOf(const RgbImage& img) {
  double s[3] = {0, 0, 0};
  for (const Color& c : img.pixels)
    for (int i = 0; i < 3; ++i) s[i] += c[i];
  double n = double(img.pixels.size());
  return Color(float(s[0] / n), float(s[1] / n), float(s[2] / n));
}

double relativeMse(const RgbImage& img, const RgbImage& ref) {
  if (img.width != ref.width || img.height != ref.height) throw std::runtime_error("relativeMse: size mismatch");
  double sum = 0;
  for (size_t i = 0; i < img.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      double x = img.pixels[i][c], r = ref.pixels[i][c];
      sum += (x - r) * (x - r) / (r * r + 0.01);
    }
  return sum / (3.0 * double(img.pixels.size()));
}

}  // namespace erpt::test
