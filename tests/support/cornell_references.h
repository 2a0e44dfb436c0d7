// The Cornell box's two references (../shared/scenes/cornell-box): Tungsten's converged render
// and a 128x128 box-filtered one. The integrators' whole-render tests check the same two things
// against them.
#pragma once

#include "erpt/render.h"

namespace erpt::test {

Scene cornellBox();
// `high` (128x128, box filter, 4x the work of `low`): channel means within `meanTolerance`
// (relative) of Tungsten's render; and the relative MSE against the 128x128 reference falling
// from `low` to `high` by a ratio in (minRatio, maxRatio) (about 4 without a bias floor).
void expectCornellBoxConverges(const RgbImage& low, const RgbImage& high, double minRatio, double maxRatio,
                               double meanTolerance = 0.01);

}  // namespace erpt::test
