// A film whose sums do not depend on the order of the adds. ERPT's chain lanes (chain_lanes.h)
// deposit into it from several threads at once, and the image must be the same bits for any
// thread count and from run to run. Floating-point sums are not associative (a double sum of
// float deposits is exact only while the pixel's total stays within 2^29 of each deposit, which
// a long render with a tent filter's small edge weights exceeds), integer sums are: each channel
// of each pixel counts multiples of `unit`, every add rounds its value to the nearest count and
// adds it atomically (or, in a chain lane's own film, plainly; the lanes' films are then added
// up, takeChunks).
//
// The owner picks unit = 2^-24 e_d (ERPT's deposit energy): a deposit's rounding error is at
// most 2^-25 e_d, below a float's precision of the deposit itself, and a pixel holds about
// 2^39 e_d. Values above kMaxCounts (2^16 e_d: only the chains of a capped seed far above e_d)
// are refused by fits(); the caller adds those to a double film in a fixed order instead, so
// the counts cannot overflow.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/byte_stream.h"
#include "erpt/image_io.h"
#include "models/film.h"

namespace erpt {

class ExactFilm {
 public:
  // concurrent: add() may be called from several threads at once.
  ExactFilm(int width, int height, double unit, bool concurrent);
  // Whether c (at any splat weight <= 1) may be added here.
  bool fits(Color c) const {
    const float m = std::max(std::max(std::abs(c.x), std::abs(c.y)), std::abs(c.z));
    return double(m) * perUnit_ < kMaxCounts;  // false for NaN too
  }
  // Adds c * weight to the pixel (thread-safe when concurrent). c must fit. (Inline: the
  // chains' deposit loop calls it for every pixel a deposit reaches.)
  void add(uint32_t pixel, Color c, float weight);
  // Adds the counts of `from` (same size and unit, not concurrent) to the pixels in
  // [firstChunk, endChunk) of kChunkPixels each, and sets them to zero there. Only the chunks
  // `from` was added to since its last takeChunks are read: a chain lane's own film touches a
  // small part of a large image between merges. Integer sums, so the result is the same as
  // if every add had been made here.
  void takeChunks(ExactFilm& from, size_t firstChunk, size_t endChunk);
  size_t chunks() const { return (size_t(width_) * size_t(height_) + kChunkPixels - 1) / kChunkPixels; }
  // Marks the chunks add() touches, for takeChunks to read only those (a lane's own film; a
  // film without the marks is read whole).
  void trackTouchedChunks() { touched_.assign(chunks(), 0); }
  static constexpr size_t kChunkPixels = 1024;
  // Asks the cache for a pixel's counts a little before adding to them: chains deposit on
  // scattered pixels, and each add would otherwise wait for its miss.
  void prefetch(uint32_t pixel) const {
    const int64_t* p = &counts_[3 * size_t(pixel)];
    __builtin_prefetch(p, 1);
    __builtin_prefetch(p + 2, 1);  // 24 bytes may straddle two cache lines
  }
  // image += sums / samplesPerPixel (image: width x height).
  void addTo(RgbImage& image, double samplesPerPixel) const;
  // film += sums, pixel by pixel (the film's sums then hold these deposits as doubles), and the
  // counts start again from zero: for owners that pick a new unit per run (PMC-ER).
  void moveInto(Film& film);
  double unit() const { return unit_; }
  void save(ByteWriter& w) const;
  void load(ByteReader& r);
  // Split renders: the counts become their total over the processes. `sum` adds vectors of
  // doubles (Film::reduce's); each count travels as two exact 32-bit halves.
  template <class Sum>
  void reduce(const Sum& sum) {
    std::vector<double> halves = splitCounts();
    sum(halves);
    joinCounts(halves);
  }

  static constexpr double kMaxCounts = double(uint64_t(1) << 40);

 private:
  std::vector<double> splitCounts() const;
  void joinCounts(const std::vector<double>& halves);
  int width_, height_;
  double unit_, perUnit_;
  bool concurrent_;
  std::vector<int64_t> counts_;  // 3 per pixel
  std::vector<uint8_t> touched_;  // per chunk when tracked: added to since takeChunks
};

inline void ExactFilm::add(uint32_t pixel, Color c, float weight) {
  const double scale = double(weight) * perUnit_;
  int64_t* p = &counts_[3 * size_t(pixel)];
  const double v[3] = {double(c.x) * scale, double(c.y) * scale, double(c.z) * scale};
  for (int k = 0; k < 3; ++k) {
    if (v[k] == 0) continue;
    const int64_t n = int64_t(std::llrint(v[k]));
    // GCC/Clang atomic builtins on plain integers (C++17 has no atomic_ref): relaxed, since
    // only the final sums are read, after the lanes have joined. A locked add costs ~20 ns
    // here, so one writer adds plainly (the integer sums are the same either way).
    if (concurrent_)
      __atomic_fetch_add(&p[k], n, __ATOMIC_RELAXED);
    else
      p[k] += n;
  }
  if (!touched_.empty()) touched_[pixel / kChunkPixels] = 1;
}

}  // namespace erpt
