// Stable stream compaction of the live slots, in two parallel passes: count survivors per
// block, then (after an exclusive scan of the block counts) scatter them in order.
#include "core/parallel.h"
#include "stages/stages.h"
#include "tracer/tracer.h"

namespace erpt {

size_t stageCompact(const PathSlotQueue& slots, const RayQueue& rays, PathSlotQueue& outSlots, RayQueue& outRays,
                    size_t count, size_t grain, uint32_t* endedPaths) {
  const size_t blocks = (count + grain - 1) / grain;
  std::vector<size_t> offset(blocks + 1, 0);
  // Each block is one task (grain 1: a block already holds `grain` slots).
  auto forEachBlock = [blocks](const auto& perBlock) {
    forEachRange("compact", blocks, 1, [&](IndexRange r) {
      for (size_t b = r.begin; b < r.end; ++b) perBlock(b);
    });
  };
  forEachBlock([&](size_t b) {
    size_t n = 0;
    for (size_t k = b * grain; k < std::min(count, (b + 1) * grain); ++k) n += slots.alive[k] != 0;
    offset[b + 1] = n;
  });
  for (size_t b = 0; b < blocks; ++b) offset[b + 1] += offset[b];
  const size_t kept = offset[blocks];
  forEachBlock([&](size_t b) {
    size_t out = offset[b];
    size_t ended = b * grain - offset[b];  // slots before this block that did not survive
    for (size_t k = b * grain; k < std::min(count, (b + 1) * grain); ++k) {
      if (!slots.alive[k]) {
        if (endedPaths) endedPaths[ended++] = slots.path[k];
        continue;
      }
      // Only the path id and the ray move: the other slot columns are per-bounce scratch
      // that the next shade pass rewrites, and a ray's time, mask, id and flags stay as
      // prepareRays set them in both queues (no stage changes them).
      outSlots.path[out] = slots.path[k];
      outSlots.alive[out] = 1;
      outRays.orgSet(out, rays.orgAt(k));
      outRays.dirSet(out, rays.dirAt(k));
      outRays.tnear[out] = rays.tnear[k];
      outRays.tfar[out] = rays.tfar[k];
      ++out;
    }
  });
  return kept;
}

}  // namespace erpt
