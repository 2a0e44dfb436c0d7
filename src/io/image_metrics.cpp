#include "erpt/image_metrics.h"

#include <cmath>
#include <string>

#include "erpt/error.h"

namespace erpt {

Color meanOf(const RgbImage& img) {
  double s[3] = {0, 0, 0};
  size_t n = 0;
  for (const Color& c : img.pixels) {
    if (!isFinite(c)) continue;
    for (int i = 0; i < 3; ++i) s[i] += c[i];
    ++n;
  }
  if (n == 0) return Color(0.0f);
  return Color(float(s[0] / double(n)), float(s[1] / double(n)), float(s[2] / double(n)));
}

std::string referenceSizeNote(const RgbImage& ref, int width, int height) {
  if (ref.width == width && ref.height == height) return "";
  matchReferenceSize(ref, width, height);  // throws for sizes that do not divide
  const int f = ref.width / width;
  return "the reference (" + std::to_string(ref.width) + "x" + std::to_string(ref.height) + ") is box-averaged over " +
         std::to_string(f) + "x" + std::to_string(f) + " pixels to the image's " + std::to_string(width) + "x" +
         std::to_string(height) + "; errors are against that average";
}

RgbImage matchReferenceSize(const RgbImage& ref, int width, int height) {
  if (ref.width == width && ref.height == height) return ref;
  if (width <= 0 || height <= 0 || ref.width % width != 0 || ref.height % height != 0 ||
      ref.width / width != ref.height / height)
    throw UsageError("image is " + std::to_string(width) + "x" + std::to_string(height) + " but the reference is " +
                     std::to_string(ref.width) + "x" + std::to_string(ref.height) +
                     " (not the same size or an integer multiple of it)");
  const int f = ref.width / width;
  RgbImage out;
  out.width = width;
  out.height = height;
  out.pixels.resize(size_t(width) * height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      double s[3] = {0, 0, 0};
      for (int j = 0; j < f; ++j)
        for (int i = 0; i < f; ++i) {
          const Color& c = ref.at(x * f + i, y * f + j);
          for (int k = 0; k < 3; ++k) s[k] += c[k];
        }
      const double inv = 1.0 / double(f * f);
      out.at(x, y) = Color(float(s[0] * inv), float(s[1] * inv), float(s[2] * inv));
    }
  return out;
}

ImageComparison compareImages(const RgbImage& img, const RgbImage& reference) {
  const RgbImage ref = matchReferenceSize(reference, img.width, img.height);
  ImageComparison out;
  double se = 0, rel = 0;
  size_t n = 0;
  for (size_t i = 0; i < img.pixels.size(); ++i) {
    if (!isFinite(img.pixels[i])) {
      ++out.nonFinite;
      continue;
    }
    if (isBlack(img.pixels[i])) {
      ++out.black;
      out.blackWhereReferenceIsNot += !isBlack(ref.pixels[i]);
    }
    for (int c = 0; c < 3; ++c) {
      const double x = img.pixels[i][c], r = ref.pixels[i][c], d2 = (x - r) * (x - r);
      se += d2;
      rel += d2 / (r * r + 0.01);
    }
    ++n;
  }
  out.mse = n ? se / (3.0 * double(n)) : 0.0;
  out.relMse = n ? rel / (3.0 * double(n)) : 0.0;
  out.mean = meanOf(img);
  out.referenceMean = meanOf(ref);
  return out;
}

}  // namespace erpt
