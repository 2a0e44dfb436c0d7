#include "models/film_splat.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"

namespace erpt {

namespace {
constexpr size_t kChunk = 4096;  // samples per accumulation buffer: fixed, so results do not depend on threads
constexpr int kMaxReach = 8;     // pixels a filter reaches per axis (gaussian radius 2: at most 5)
constexpr size_t kMergeRows = 16;  // rows per task when the chunk buffers are added to the film

// Integral of the 1D filter over offsets [a, b] from the centre, by the midpoint rule.
double integral(const PixelFilter& f, double a, double b) {
  const int n = 1024;
  double s = 0;
  for (int i = 0; i < n; ++i) s += f.eval(float(a + (b - a) * (i + 0.5) / n));
  return s * (b - a) / n;
}

// The pixels [lo, hi] along one axis a sample at x reaches, within [0, size).
void reach(float x, float r, int size, int& lo, int& hi) {
  lo = std::max(0, int(std::floor(x - 0.5f - r)) + 1);
  hi = std::min(size - 1, int(std::floor(x - 0.5f + r)));
  hi = std::min(hi, lo + kMaxReach - 1);
}

}  // namespace

const char* filmModeName(FilmMode m) {
  switch (m) {
    case FilmMode::Auto: return "auto";
    case FilmMode::Fis: return "fis";
    case FilmMode::Splat: return "splat";
    case FilmMode::SplatUnbiased: return "splat-unbiased";
  }
  return "?";
}

FilmMode filmModeFor(FilmMode requested, FilterKind filter) {
  if (requested != FilmMode::Auto) return requested;
  // Box: splatting and importance sampling are the same estimator. Tent and gaussian: docs/film-splatting.md.
  return filter == FilterKind::Box ? FilmMode::Fis : FilmMode::Splat;
}

SplatFilm::SplatFilm(const PixelFilter& filter, int width, int height)
    : filter_(filter), width_(width), height_(height) {
  const double r = filter.radius();
  norm_ = float(1.0 / integral(filter, -r, r));
  sum_.assign(size_t(width) * size_t(height) * 3, 0.0);
  weight_.assign(size_t(width) * size_t(height), 0.0);
  auto inside = [&](int size) {
    std::vector<double> c(static_cast<size_t>(size), 0.0);
    for (int p = 0; p < size; ++p) {
      const double centre = p + 0.5;
      // Offsets from the centre: the filter's support clipped to the film [0, size).
      c[size_t(p)] = integral(filter, std::max(-r, -centre), std::min(r, double(size) - centre)) * norm_;
    }
    return c;
  };
  insideX_ = inside(width);
  insideY_ = inside(height);
}

template <class Add>
void SplatFilm::splatOne(float x, float y, Add&& add) const {
  const float radius = filter_.radius();
  int px0, px1, py0, py1;
  reach(x, radius, width_, px0, px1);
  reach(y, radius, height_, py0, py1);
  float wx[kMaxReach], wy[kMaxReach];
  for (int p = px0; p <= px1; ++p) wx[p - px0] = filter_.eval(x - (float(p) + 0.5f)) * norm_;
  for (int p = py0; p <= py1; ++p) wy[p - py0] = filter_.eval(y - (float(p) + 0.5f)) * norm_;
  for (int py = py0; py <= py1; ++py)
    for (int px = px0; px <= px1; ++px) {
      const double w = double(wx[px - px0]) * wy[py - py0];
      if (w > 0) add(px, py, w);
    }
}

void SplatFilm::addSamples(const float* x, const float* y, const float* r, const float* g, const float* b, size_t n) {
  const size_t chunks = (n + kChunk - 1) / kChunk;
  // The buffers are kept from call to call: allocating them afresh for every batch cost a
  // page fault per touched page (docs/performance.md).
  if (chunkBuffers_.size() < chunks) chunkBuffers_.resize(chunks);
  const float radius = filter_.radius();
  forEachRange("splat", chunks, 1, [&](IndexRange range) {
    for (size_t c = range.begin; c < range.end; ++c) {
      const size_t begin = c * kChunk, end = std::min(n, begin + kChunk);
      ChunkBuffer& buf = chunkBuffers_[c];
      int xlo = width_, xhi = -1, ylo = height_, yhi = -1;
      for (size_t i = begin; i < end; ++i) {
        int a, e;
        reach(x[i], radius, width_, a, e);
        xlo = std::min(xlo, a), xhi = std::max(xhi, e);
        reach(y[i], radius, height_, a, e);
        ylo = std::min(ylo, a), yhi = std::max(yhi, e);
      }
      if (xhi < xlo || yhi < ylo) {
        buf.w = buf.h = 0;
        continue;
      }
      buf.x0 = xlo, buf.y0 = ylo, buf.w = xhi - xlo + 1, buf.h = yhi - ylo + 1;
      buf.v.assign(size_t(buf.w) * size_t(buf.h) * 4, 0.0);
      for (size_t i = begin; i < end; ++i) {
        if (!std::isfinite(r[i]) || !std::isfinite(g[i]) || !std::isfinite(b[i])) continue;
        splatOne(x[i], y[i], [&](int px, int py, double w) {
          double* v = &buf.v[(size_t(py - buf.y0) * size_t(buf.w) + size_t(px - buf.x0)) * 4];
          v[0] += w * r[i], v[1] += w * g[i], v[2] += w * b[i], v[3] += w;
        });
      }
    }
  });
  // Merged in bands of rows, in parallel; within a band the buffers are added in chunk order,
  // so every pixel sees the same sequence of additions for any thread count.
  const size_t bands = (size_t(height_) + kMergeRows - 1) / kMergeRows;
  forEachRange("splat merge", bands, 1, [&](IndexRange range) {
    const int rowBegin = int(range.begin * kMergeRows), rowEnd = int(std::min(size_t(height_), range.end * kMergeRows));
    for (size_t c = 0; c < chunks; ++c) {
      const ChunkBuffer& buf = chunkBuffers_[c];
      const int j0 = std::max(0, rowBegin - buf.y0), j1 = std::min(buf.h, rowEnd - buf.y0);
      for (int j = j0; j < j1; ++j)
        for (int i = 0; i < buf.w; ++i) {
          const double* v = &buf.v[(size_t(j) * size_t(buf.w) + size_t(i)) * 4];
          const size_t p = size_t(buf.y0 + j) * size_t(width_) + size_t(buf.x0 + i);
          sum_[3 * p] += v[0], sum_[3 * p + 1] += v[1], sum_[3 * p + 2] += v[2];
          weight_[p] += v[3];
        }
    }
  });
}

void SplatFilm::addScattered(const float* x, const float* y, const float* r, const float* g, const float* b, size_t n) {
  for (size_t i = 0; i < n; ++i) {
    if (!std::isfinite(r[i]) || !std::isfinite(g[i]) || !std::isfinite(b[i])) continue;
    splatOne(x[i], y[i], [&](int px, int py, double w) {
      const size_t p = size_t(py) * size_t(width_) + size_t(px);
      sum_[3 * p] += w * r[i], sum_[3 * p + 1] += w * g[i], sum_[3 * p + 2] += w * b[i];
      weight_[p] += w;
    });
  }
}

RgbImage SplatFilm::resolve(FilmMode mode, double spp) const {
  RgbImage img;
  img.width = width_;
  img.height = height_;
  img.pixels.resize(size_t(width_) * size_t(height_));
  for (int py = 0; py < height_; ++py)
    for (int px = 0; px < width_; ++px) {
      const size_t p = size_t(py) * size_t(width_) + size_t(px);
      const double d = mode == FilmMode::SplatUnbiased ? spp * insideX_[size_t(px)] * insideY_[size_t(py)] : weight_[p];
      const double inv = d > 0 ? 1.0 / d : 0.0;
      img.pixels[p] = Color(float(sum_[3 * p] * inv), float(sum_[3 * p + 1] * inv), float(sum_[3 * p + 2] * inv));
    }
  return img;
}

}  // namespace erpt
