// Film splatting for the path tracer (`--film splat|splat-unbiased`; docs/film-splatting.md).
// Film positions are uniform in each pixel (stratified); every sample is added to each pixel
// its filter reaches with the normalized filter's weight h(x - c_j). Two estimates:
//   Splat (Mitsuba's and pbrt-v3's): pixel = sum of w L / sum of w. Consistent, not unbiased
//     (a ratio of estimates); lowest variance where the image is smooth.
//   SplatUnbiased: pixel = sum of w L / (spp C_j), C_j the part of the normalized filter over
//     pixel j that lies inside the image (1 away from the border). Unbiased for the filtered
//     image restricted to the film.
// Filter importance sampling (Fis: each sample counts in its own pixel, positions drawn from
// the filter) is the other film; ERPT and PMC-ER always use it (their seeds' film density).
// Samples are accumulated in fixed chunks, each into its own buffer in parallel, and the
// buffers are merged in chunk order: the image does not depend on the thread count.
#pragma once

#include <cstdint>
#include <vector>

#include "core/byte_stream.h"
#include "erpt/image_io.h"
#include "models/pixel_filter.h"

namespace erpt {

const char* filmModeName(FilmMode m);
// What Auto means for a filter (chosen by measurement: docs/film-splatting.md).
FilmMode filmModeFor(FilmMode requested, FilterKind filter);

class SplatFilm {
 public:
  SplatFilm(const PixelFilter& filter, int width, int height);
  // Adds samples [0, n): film positions and radiance columns. Non-finite radiance is dropped
  // (the path tracer counts it).
  void addSamples(const float* x, const float* y, const float* r, const float* g, const float* b, size_t n);
  // The same for samples scattered over the image (BDPT's light tracing), added one by one on
  // the calling thread: addSamples' per-chunk buffers would each span the whole image.
  void addScattered(const float* x, const float* y, const float* r, const float* g, const float* b, size_t n);
  RgbImage resolve(FilmMode mode, double samplesPerPixel) const;
  void save(ByteWriter& w) const {
    w.putVector(sum_);
    w.putVector(weight_);
  }
  void load(ByteReader& r) {
    r.getVector(sum_, sum_.size());
    r.getVector(weight_, weight_.size());
  }
  template <class Sum>
  void reduce(const Sum& sum) {
    sum(sum_);
    sum(weight_);
  }

 private:
  // Calls add(px, py, w) for every pixel the sample at (x, y) reaches, w its normalized filter weight.
  template <class Add>
  void splatOne(float x, float y, Add&& add) const;
  // One chunk's samples accumulated over the bounding box of the pixels they reach.
  struct ChunkBuffer {
    int x0 = 0, y0 = 0, w = 0, h = 0;
    std::vector<double> v;  // r, g, b, weight per pixel
  };
  const PixelFilter& filter_;
  int width_, height_;
  float norm_;                     // 1 / integral of the 1D filter
  std::vector<double> sum_, weight_;  // 3 and 1 per pixel
  std::vector<double> insideX_, insideY_;  // C per column and row
  std::vector<ChunkBuffer> chunkBuffers_;  // addSamples' scratch, kept between calls
};

}  // namespace erpt
