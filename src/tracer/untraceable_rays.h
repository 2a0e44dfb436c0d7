// Rays the tracer refuses to hand to Embree: a non-finite or zero direction, a non-finite
// origin, or a NaN interval. Debian's Embree asserts (and aborts the process) on such rays in
// its AVX-512 kernels, and on other machines returns hits that mean nothing, so the check is
// ours and runs on every CPU. Tracer-internal.
#pragma once

#include <cstdint>
#include <vector>

#include "tracer/ray_queues.h"

namespace erpt {

// Whether ray i may be traced: well formed, or disabled (tnear > tfar: Embree skips it).
bool isTraceable(const RayQueue& rays, size_t i);

// Disables every ray of rays[range] that is not well formed, with finite columns, and appends
// the indices of those that were enabled (the refused rays) to `refused`. Returns how many
// it refused.
size_t refuseUntraceableRays(RayQueue& rays, IndexRange range, std::vector<uint32_t>& refused);

}  // namespace erpt
