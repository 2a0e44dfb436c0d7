// Per-pixel sample sums. With filter importance sampling every sample counts fully in the
// pixel it was generated for, so a pixel's value is the mean of its samples. Samples are
// added pixel by pixel in sample order, so the sums do not depend on thread count.
#pragma once

#include <vector>

#include "core/byte_stream.h"
#include "erpt/image_io.h"

namespace erpt {

class Film {
 public:
  Film(int width, int height) : width_(width), height_(height), sum_(size_t(width) * height * 3, 0.0) {}
  int width() const { return width_; }
  int height() const { return height_; }
  void add(uint32_t pixel, Color c) {
    sum_[3 * size_t(pixel)] += c.x;
    sum_[3 * size_t(pixel) + 1] += c.y;
    sum_[3 * size_t(pixel) + 2] += c.z;
  }
  // Asks the cache for a pixel's sums ahead of an add (see ExactFilm::prefetch).
  void prefetch(uint32_t pixel) const {
    const double* p = &sum_[3 * size_t(pixel)];
    __builtin_prefetch(p, 1);
    __builtin_prefetch(p + 2, 1);
  }
  // Adds double-precision sums (an ExactFilm's, exact_film.h).
  void addSums(size_t pixel, double r, double g, double b) {
    sum_[3 * pixel] += r;
    sum_[3 * pixel + 1] += g;
    sum_[3 * pixel + 2] += b;
  }
  // A NaN/Inf estimate is dropped, never accumulated; returns false then (callers count them).
  bool addIfFinite(uint32_t pixel, Color c) {
    if (!isFinite(c)) return false;
    add(pixel, c);
    return true;
  }
  RgbImage resolve(double samplesPerPixel) const;
  void save(ByteWriter& w) const { w.putVector(sum_); }
  // Split renders: `sum` replaces the sums by their total over the processes.
  template <class Sum>
  void reduce(const Sum& sum) { sum(sum_); }
  void load(ByteReader& r) { r.getVector(sum_, sum_.size()); }

 private:
  int width_, height_;
  std::vector<double> sum_;
};

}  // namespace erpt
