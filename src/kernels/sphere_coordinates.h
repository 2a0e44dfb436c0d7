// sphereCoordinates (models/surface.h) for many hits at once: the two atan2s of each hit in
// vector lanes. The tracer turns every sphere hit into sphere coordinates; one at a time,
// glibc's atan2f is a long scalar call.
#pragma once

#include <cstddef>

namespace erpt {

// (u[j], v[j]) for the point whose direction from its sphere's centre, in the sphere's frame,
// is (x[j], y[j], z[j]), j < n: u = azimuth / 2 pi in [0, 1), v = polar angle / pi. Agrees
// with sphereCoordinates to a few units in the last place (tests/kernels).
void sphereCoordinatesOf(const float* x, const float* y, const float* z, size_t n, float* u, float* v);

}  // namespace erpt
