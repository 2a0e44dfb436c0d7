// BDPT's stage kernels (docs/bdpt.md). A task takes a chunk of samples; for each it walks a
// light subpath and a camera subpath (bdpt_walk.cpp: start, then intersect -> extend per
// bounce over the live walks, rays traced in streams), then connects them by every strategy
// (bdpt_connect.cpp: the connections' shadow rays in one stream) and resolves what arrives.
#pragma once

#include <vector>

#include "core/queues.h"
#include "core/seeds.h"
#include "kernels/bdpt_vertex.h"
#include "stages/stages.h"
#include "tracer/ray_queues.h"

namespace erpt {

struct BdptContext {
  const StageContext& stage;
  int height;
  // Strategies a render keeps (the others are left out, unweighted ones are not MIS-weighted):
  // for tests that check one strategy (s, t) at a time. -1: all.
  int onlyS = -1, onlyT = -1;
  bool unweighted = false;
};

// Random numbers of a sample's light subpath: a stream of its own, keyed like the camera's.
uint64_t lightSubpathKey(uint64_t seed, uint32_t pixel, uint32_t sample);
// The stream a sample's light subpath draws from: lightSubpathKey, or, replaying primary
// samples, its chain's light-subpath stream (sampleStream's for the camera subpath).
uint64_t lightSubpathStream(const StageContext& ctx, uint32_t pixel, uint32_t sample);

// The subpaths of a chunk of samples: every vertex in one queue (appended as the walks make
// them, linked by `parent`), and per sample its pixel, stratum, film position and newest vertex
// of each subpath.
struct BdptSubpaths {
  BdptVertexQueue vertices;
  size_t used = 0;
  std::vector<uint32_t> pixel, sample;
  std::vector<float> filmX, filmY;
  std::vector<int32_t> lightEnd, cameraEnd;
  std::vector<float> lightNextEvent;  // next-event density of the light vertex from the light subpath's second vertex
  std::vector<uint8_t> invalid;       // a ray was refused: the sample is dropped
  // Multiplexed MLT (mmlt) takes one strategy (s, t) per sample: its light subpath stops at s
  // vertices, its camera subpath at t, and only that strategy is formed. Empty (every
  // sample of a BDPT render): all strategies, subpaths as long as the walks go.
  std::vector<int16_t> strategyS, strategyT;
  void resizeSamples(size_t n);
  // Room for `more` vertices after `used`.
  void reserveVertices(size_t more);
};

enum class BdptSide { Light, Camera };

// The most vertices sample i's subpath on `side` may have (-1: no limit): its strategy's s or t.
inline int bdptVertexCap(const BdptSubpaths& paths, BdptSide side, size_t i) {
  const std::vector<int16_t>& cap = side == BdptSide::Light ? paths.strategyS : paths.strategyT;
  return cap.empty() ? -1 : cap[i];
}

// Whether the walk of sample i on `side`, its newest vertex at `depth` segments, samples a
// bounce: the light subpath needs no more than maxDepth vertices (t >= 1), the camera subpath
// no more than maxDepth + 1, and a sample of one strategy no more than its s or t.
inline bool bdptWalkContinues(const BdptContext& ctx, BdptSide side, const BdptSubpaths& paths, size_t i,
                              uint32_t depth) {
  const int maxDepth = ctx.stage.maxDepth;
  if (maxDepth >= 0 && int(depth) + (side == BdptSide::Light ? 1 : 0) >= maxDepth) return false;
  const int cap = bdptVertexCap(paths, side, i);
  return cap < 0 || int(depth) + 1 < cap;
}

// Starts the walks of samples [range) in walk slots of the same index: the light vertex (or
// the eye vertex, with its camera ray) at vertices[base + i], and the ray; alive[i] says
// whether there is a ray to trace.
void stageBdptStartLight(const BdptContext& ctx, BdptSubpaths& paths, BdptWalkQueue& walks, RayQueue& rays,
                         size_t base, std::vector<uint8_t>& alive, IndexRange range);
void stageBdptStartCamera(const BdptContext& ctx, BdptSubpaths& paths, BdptWalkQueue& walks, RayQueue& rays,
                          size_t base, std::vector<uint8_t>& alive, IndexRange range);
// One bounce of the live walks [range): the hit becomes vertex vertices[base + k] (a camera
// ray that escapes becomes an environment vertex, if the scene has one), the BSDF samples
// the next direction (from the light: with the adjoint BSDF), Russian roulette; the walk's
// ray is set in place and alive[k] says whether it goes on.
void stageBdptExtend(const BdptContext& ctx, BdptSide side, BdptSubpaths& paths, BdptWalkQueue& walks, RayQueue& rays,
                     const HitQueue& hits, size_t base, std::vector<uint8_t>& alive, IndexRange range);

// Working memory of the connection stage (per task), and the vertices it makes that belong to
// no subpath (`extra`: lens points of light tracing, next-event light points).
struct BdptConnectScratch {
  std::vector<BdptVertexQueue::Row> light, camera;
  std::vector<VertexBsdf> lightBsdf, cameraBsdf;
  // Per vertex j >= 1 with a BSDF: the unit direction towards vertex j - 1 of its subpath (the
  // camera side for a camera vertex, the light side for a light vertex) in the vertex's frame,
  // shared by all the vertex's connections.
  std::vector<Vec3> lightBackLocal, cameraBackLocal;
  std::vector<int32_t> lightIndex, cameraIndex;
  std::vector<float> cameraDensity, lightDensity;
  std::vector<uint8_t> specular;
  BdptVertexQueue extra;
  size_t extraUsed = 0;
};
// Every strategy of samples [range): appends a contribution (value, MIS weight, ends, shadow
// ray: disabled for s = 0) to `connections` and `rays` (grown as needed), and sets radiance[i]
// to 0 (NaN for a sample a refused ray made invalid). The caller resets scratch.extraUsed.
void stageBdptConnect(const BdptContext& ctx, const BdptSubpaths& paths, BdptConnectScratch& scratch,
                      std::vector<Color>& radiance, BdptConnectionQueue& connections, RayQueue& rays, IndexRange range);

// ERPT's seeds: every unoccluded contribution in connections [0, n) as a complete path (eye
// first, light last) with its energy and film position, appended to `store` in order.
// `firstSample` numbers the chunk's samples within their run.
void stageBdptRecordSeeds(const BdptContext& ctx, const BdptSubpaths& paths, const BdptConnectScratch& scratch,
                          const BdptConnectionQueue& connections, const RayQueue& rays, size_t n, size_t firstSample,
                          SeedStore& store);

}  // namespace erpt
