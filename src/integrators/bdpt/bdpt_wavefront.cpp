#include "integrators/bdpt/bdpt_wavefront.h"

#include <chrono>

namespace erpt {

namespace {
double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

size_t compactWalks(BdptWalkQueue& walks, RayQueue& rays, const std::vector<uint8_t>& alive, size_t live) {
  size_t kept = 0;
  for (size_t k = 0; k < live; ++k) {
    if (!alive[k]) continue;
    if (kept != k) {
      walks.copyRow(kept, walks, k);
      rays.copyRow(kept, rays, k);
    }
    ++kept;
  }
  return kept;
}

void BdptWavefront::prepare(size_t n) {
  paths.resizeSamples(n);
  for (auto* q : {&rays, &shadowRays})
    if (q->size() < n) prepareRays(*q, n);
  if (walks.size() < n) walks.resize(n);
  if (hits.size() < n) hits.resize(n);
  alive.resize(n);
}

uint64_t walkSubpaths(const Tracer& tracer, const BdptContext& ctx, BdptSide side, BdptWavefront& w, size_t n,
                      StageTimes& times) {
  auto start = std::chrono::steady_clock::now();
  w.paths.reserveVertices(n);
  if (side == BdptSide::Light)
    stageBdptStartLight(ctx, w.paths, w.walks, w.rays, w.paths.used, w.alive, IndexRange{0, n});
  else
    stageBdptStartCamera(ctx, w.paths, w.walks, w.rays, w.paths.used, w.alive, IndexRange{0, n});
  w.paths.used += n;
  size_t live = compactWalks(w.walks, w.rays, w.alive, n);
  times.add(side == BdptSide::Light ? "light start" : "camera start", secondsSince(start));
  uint64_t rays = 0;
  bool first = side == BdptSide::Camera;
  while (live > 0) {
    start = std::chrono::steady_clock::now();
    tracer.intersect(w.rays, w.hits, IndexRange{0, live}, first ? RayCoherence::Coherent : RayCoherence::Incoherent);
    times.add("intersect", secondsSince(start));
    rays += live;
    first = false;
    start = std::chrono::steady_clock::now();
    w.paths.reserveVertices(live);
    stageBdptExtend(ctx, side, w.paths, w.walks, w.rays, w.hits, w.paths.used, w.alive, IndexRange{0, live});
    w.paths.used += live;
    live = compactWalks(w.walks, w.rays, w.alive, live);
    times.add(side == BdptSide::Light ? "light extend" : "camera extend", secondsSince(start));
  }
  return rays;
}

uint64_t connectSubpaths(const Tracer& tracer, const BdptContext& ctx, BdptWavefront& w, size_t n, StageTimes& times) {
  auto start = std::chrono::steady_clock::now();
  w.radiance.assign(n, Color(0.0f));
  w.connections.resize(0);
  w.scratch.extraUsed = 0;
  stageBdptConnect(ctx, w.paths, w.scratch, w.radiance, w.connections, w.shadowRays, IndexRange{0, n});
  times.add("connect", secondsSince(start));
  const size_t m = w.connections.size();
  start = std::chrono::steady_clock::now();
  uint64_t rays = 0;
  for (size_t c = 0; c < m; ++c) rays += w.shadowRays.tnear[c] <= w.shadowRays.tfar[c];  // s = 0 traces none
  tracer.occluded(w.shadowRays, IndexRange{0, m});
  times.add("shadow", secondsSince(start));
  return rays;
}

}  // namespace erpt
