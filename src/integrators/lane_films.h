// Films of their own for chain lanes (ChainLanes, PmcPopulation). Lanes on several threads that
// share one ExactFilm add with locked instructions and move its cache lines between the
// threads: on 2 threads ERPT's deposit stage took 1.6x the time it takes on one. With a film
// per lane the adds are plain; the owner adds the lanes' films into its own at the points where
// it reads it (integer sums: the same bits as if every lane had added there, so the image does
// not depend on the thread count). Only while one film per lane fits in a memory budget;
// otherwise the lanes share the owner's film.
#pragma once

#include <vector>

#include "erpt/stage_times.h"
#include "models/exact_film.h"

namespace erpt {

class LaneFilms {
 public:
  // Whether `lanes` films of width x height fit the budget (and are worth it: lanes > 1).
  static bool fit(size_t lanes, int width, int height);
  // No films until reset.
  LaneFilms() = default;
  // One film per lane, empty, in `unit`, when they fit; none otherwise.
  void reset(size_t lanes, int width, int height, double unit);
  bool active() const { return !films_.empty(); }
  double unit() const { return films_.empty() ? 0.0 : films_[0].unit(); }
  // The film lane `lane` deposits into: its own, or `shared` (which must then be concurrent).
  ExactFilm& of(size_t lane, ExactFilm& shared) { return films_.empty() ? shared : films_[lane]; }
  // Adds every lane's film into `target` and empties them, in parallel over chunks of pixels.
  void mergeInto(ExactFilm& target, StageTimes* times);

 private:
  std::vector<ExactFilm> films_;
};

}  // namespace erpt
