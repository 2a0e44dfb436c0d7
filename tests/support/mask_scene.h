// A plane cut into a 4x4 checkerboard by a `mask` (opacity 1 / 0) over a floor, lit by a small
// area light above and a dim constant environment; and the same picture with the plane's eight
// opaque squares as geometry instead of the mask.
#pragma once

#include <string>

#include "support/test_support.h"

namespace erpt::test {

// Writes the scene into `dir`; cutGeometry: the squares as an OBJ instead of the mask.
std::string writeCheckerMaskScene(const TempDir& dir, bool cutGeometry);

}  // namespace erpt::test
