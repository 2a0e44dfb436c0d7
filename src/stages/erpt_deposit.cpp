// ERPT deposit stage: the step's deposit records go to the film one slot after another, so
// the sums (and the image) do not depend on how the other stages were split over threads.
#include "erpt/erpt_stages.h"

namespace erpt {

double applyDeposits(const DepositQueue& deposits, size_t count, const FilmDensity& density, Film& film) {
  double total = 0;
  auto splat = [&](float x, float y, Color c) {
    if (isBlack(c)) return;
    total += luminance(c);
    density.splat(x, y, [&](uint32_t pixel, float w) { film.add(pixel, c * w); });
  };
  for (size_t i = 0; i < count; ++i) {
    splat(deposits.x0[i], deposits.y0[i], Color(deposits.r0[i], deposits.g0[i], deposits.b0[i]));
    splat(deposits.x1[i], deposits.y1[i], Color(deposits.r1[i], deposits.g1[i], deposits.b1[i]));
  }
  return total;
}

}  // namespace erpt
