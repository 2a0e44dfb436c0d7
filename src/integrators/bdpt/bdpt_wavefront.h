// The queues of one BDPT task and the two halves of its work on a chunk of samples: walking
// the subpaths (bounce by bounce, rays in streams) and connecting them (every strategy, the
// shadow rays in one stream). The integrator (bdpt_integrator.cpp) resolves what arrives;
// bench/bm_bdpt.cpp times each half.
#pragma once

#include <vector>

#include "erpt/stage_times.h"
#include "stages/bdpt_stages.h"
#include "tracer/tracer.h"

namespace erpt {

// One task's queues, kept per thread across chunks.
struct BdptWavefront {
  BdptSubpaths paths;
  BdptWalkQueue walks;
  RayQueue rays, shadowRays;
  HitQueue hits;
  std::vector<uint8_t> alive;
  BdptConnectScratch scratch;
  BdptConnectionQueue connections;
  std::vector<Color> radiance;
  // Sizes the queues for a chunk of n samples (the caller then sets paths.pixel and .sample).
  void prepare(size_t n);
};

// Keeps the first `live` walks with alive[k] set, in order, with their rays; returns how many.
size_t compactWalks(BdptWalkQueue& walks, RayQueue& rays, const std::vector<uint8_t>& alive, size_t live);

// Walks one side's subpaths of the chunk's n samples (w.paths holds their pixels and strata)
// to their ends. Returns the rays traced.
uint64_t walkSubpaths(const Tracer& tracer, const BdptContext& ctx, BdptSide side, BdptWavefront& w, size_t n,
                      StageTimes& times);
// Forms every strategy of the chunk's n walked samples (w.connections, w.radiance) and traces
// the shadow rays (w.shadowRays: tfar < 0 where occluded). Returns the rays traced.
uint64_t connectSubpaths(const Tracer& tracer, const BdptContext& ctx, BdptWavefront& w, size_t n, StageTimes& times);

}  // namespace erpt
