#include "models/film.h"

namespace erpt {

RgbImage Film::resolve(double samplesPerPixel) const {
  RgbImage img;
  img.width = width_;
  img.height = height_;
  img.pixels.resize(size_t(width_) * height_);
  double inv = samplesPerPixel > 0 ? 1.0 / samplesPerPixel : 0.0;
  for (size_t i = 0; i < img.pixels.size(); ++i)
    img.pixels[i] = Color(float(sum_[3 * i] * inv), float(sum_[3 * i + 1] * inv), float(sum_[3 * i + 2] * inv));
  return img;
}

}  // namespace erpt
