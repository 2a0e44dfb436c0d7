// A render's state between sample passes, as checkpoints keep it.
#pragma once

#include <cstdint>
#include <vector>

namespace erpt {

// A render's state after a whole number of sample passes (pass j gives every pixel its
// sample j, so after k passes every pixel has k samples): what a checkpoint holds, and what a
// render stopped part-way through a pass falls back to. `bytes` is the integrator's own
// layout (film sums, chain counters, statistics; sample_passes.h).
struct RenderState {
  int passesDone = 0;
  std::vector<uint8_t> bytes;
};

}  // namespace erpt
