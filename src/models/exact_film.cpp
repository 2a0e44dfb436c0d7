#include "models/exact_film.h"

#include <cmath>

namespace erpt {

ExactFilm::ExactFilm(int width, int height, double unit, bool concurrent)
    : width_(width),
      height_(height),
      unit_(unit),
      perUnit_(1.0 / unit),
      concurrent_(concurrent),
      counts_(size_t(width) * size_t(height) * 3, 0) {}

void ExactFilm::takeChunks(ExactFilm& from, size_t firstChunk, size_t endChunk) {
  const size_t pixels = counts_.size() / 3;
  for (size_t chunk = firstChunk; chunk < endChunk; ++chunk) {
    if (!from.touched_.empty()) {
      if (!from.touched_[chunk]) continue;
      from.touched_[chunk] = 0;
    }
    const size_t begin = 3 * chunk * kChunkPixels, end = 3 * std::min(pixels, (chunk + 1) * kChunkPixels);
    for (size_t i = begin; i < end; ++i) {
      if (concurrent_)
        __atomic_fetch_add(&counts_[i], from.counts_[i], __ATOMIC_RELAXED);
      else
        counts_[i] += from.counts_[i];
      from.counts_[i] = 0;
    }
    if (!touched_.empty()) touched_[chunk] = 1;
  }
}

void ExactFilm::addTo(RgbImage& image, double samplesPerPixel) const {
  const double scale = samplesPerPixel > 0 ? unit_ / samplesPerPixel : 0.0;
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    Color& c = image.pixels[i];
    c.x = float(double(c.x) + double(counts_[3 * i]) * scale);
    c.y = float(double(c.y) + double(counts_[3 * i + 1]) * scale);
    c.z = float(double(c.z) + double(counts_[3 * i + 2]) * scale);
  }
}

void ExactFilm::moveInto(Film& film) {
  for (size_t i = 0; i < counts_.size() / 3; ++i) {
    film.addSums(i, double(counts_[3 * i]) * unit_, double(counts_[3 * i + 1]) * unit_, double(counts_[3 * i + 2]) * unit_);
    counts_[3 * i] = counts_[3 * i + 1] = counts_[3 * i + 2] = 0;
  }
}

void ExactFilm::save(ByteWriter& w) const {
  w.put(unit_);
  w.putVector(counts_);
}

void ExactFilm::load(ByteReader& r) {
  r.get(unit_);
  perUnit_ = 1.0 / unit_;
  r.getVector(counts_, counts_.size());
}

std::vector<double> ExactFilm::splitCounts() const {
  std::vector<double> halves(2 * counts_.size());
  for (size_t i = 0; i < counts_.size(); ++i) {
    const uint64_t u = uint64_t(counts_[i]);
    halves[2 * i] = double(int64_t(u) >> 32);  // signed high half
    halves[2 * i + 1] = double(u & 0xffffffffu);
  }
  return halves;
}

void ExactFilm::joinCounts(const std::vector<double>& halves) {
  // Sums of up to 2^21 processes' halves are exact in a double; the wrap-around arithmetic of
  // uint64 puts them back together.
  for (size_t i = 0; i < counts_.size(); ++i)
    counts_[i] = int64_t((uint64_t(int64_t(halves[2 * i])) << 32) + uint64_t(int64_t(halves[2 * i + 1])));
}

}  // namespace erpt
