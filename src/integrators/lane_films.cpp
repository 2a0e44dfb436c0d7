#include "integrators/lane_films.h"

#include <cstdint>

#include "core/parallel.h"

namespace erpt {

namespace {
// The lanes' films together take at most this much memory.
constexpr double kLaneFilmBytes = 256.0 * 1024 * 1024;
}  // namespace

bool LaneFilms::fit(size_t lanes, int width, int height) {
  return lanes > 1 && double(lanes) * double(width) * double(height) * 3 * sizeof(int64_t) <= kLaneFilmBytes;
}

void LaneFilms::reset(size_t lanes, int width, int height, double unit) {
  films_.clear();
  if (!fit(lanes, width, height)) return;
  for (size_t l = 0; l < lanes; ++l) {
    films_.emplace_back(width, height, unit, false);
    films_.back().trackTouchedChunks();
  }
}

void LaneFilms::mergeInto(ExactFilm& target, StageTimes* times) {
  if (films_.empty()) return;
  forEachRange("chain deposit merge", target.chunks(), 16, [&](IndexRange r) {
    for (ExactFilm& film : films_) target.takeChunks(film, r.begin, r.end);
  }, times);
}

}  // namespace erpt
