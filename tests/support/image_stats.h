// Image comparisons used by the statistical tests (the library's metrics, under short names).
#pragma once

#include "erpt/image_metrics.h"

namespace erpt::test {

using erpt::meanOf;
// Mean over pixels and channels of (x - r)^2 / (r^2 + 0.01); sizes must agree.
double relativeMse(const RgbImage& img, const RgbImage& ref);

}  // namespace erpt::test
