// Image comparisons used by the statistical tests.
#pragma once

#include "erpt/image_io.h"

namespace erpt::test {

Color meanOf(const RgbImage& img);
// Mean over pixels and channels of (x - r)^2 / (r^2 + 0.01).
double relativeMse(const RgbImage& img, const RgbImage& ref);

}  // namespace erpt::test
