// Seed recording: turns this bounce's contributions into complete seed paths, at rows fixed
// by the slot order (so the seed store's order does not depend on the threads); it only runs
// when ERPT (or a test) asks for seeds.
#include "stages/stages.h"

namespace erpt {

namespace {

bool hitEmitter(const PathSlotQueue& slots, size_t k) { return slots.emitWeight[k] > 0; }
bool connectedToLight(const PathSlotQueue& slots, const RayQueue& shadowRays, size_t k) {
  return slots.neeWeight[k] > 0 && shadowRays.tfar[k] >= 0;
}

// The number of vertices of the history chain ending at `last` (eye included).
uint32_t chainLength(const VertexQueue& history, int32_t last) {
  uint32_t n = 0;
  for (int32_t v = last; v >= 0; v = history.parent[v]) ++n;
  return n;
}

// Writes the n-vertex history chain ending at `last` to rows [begin, begin + n) of the store,
// eye first.
void copyChain(const VertexQueue& history, int32_t last, uint32_t n, VertexQueue& out, uint32_t begin) {
  int32_t v = last;
  for (uint32_t j = n; j-- > 0; v = history.parent[v]) {
    out.copyRow(begin + j, history, size_t(v));
    out.parent[begin + j] = j == 0 ? -1 : int32_t(begin + j - 1);
  }
}

struct SeedFacts {
  bool explicitLight;
  float weight;
  Color estimate;
  float pLength, pLight;
};

void writeSeed(SeedStore& store, size_t row, const PathQueue& paths, uint32_t id, const SeedFacts& f, uint32_t begin,
               uint32_t count) {
  SeedQueue::Row seed;
  seed.pixel = paths.pixel[id];
  seed.path = paths.runIndex[id];
  seed.filmX = paths.filmX[id];
  seed.filmY = paths.filmY[id];
  seed.explicitLight = f.explicitLight;
  seed.misWeight = f.weight;
  seed.estimate = f.estimate;
  seed.pLength = f.pLength;
  seed.pLight = f.pLight;
  seed.vertexBegin = begin;
  seed.vertexCount = count;
  store.seeds.setRow(row, seed);
}

}  // namespace

void stageCountSeeds(const PathSlotQueue& slots, const RayQueue& shadowRays, const VertexHistory& history,
                     SeedPlacement& placement, IndexRange range) {
  for (size_t k = range.begin; k < range.end; ++k) {
    const bool emitted = hitEmitter(slots, k), connected = connectedToLight(slots, shadowRays, k);
    const uint32_t n = emitted || connected ? chainLength(*history.vertices, int32_t(history.base + k)) : 0;
    placement.seed[k] = uint32_t(emitted) + uint32_t(connected);
    // A next-event seed adds the light point to the chain.
    placement.vertex[k] = (emitted ? n : 0) + (connected ? n + 1 : 0);
  }
}

void placeSeeds(size_t live, SeedPlacement& placement, SeedStore& store) {
  uint32_t seedRow = uint32_t(store.seeds.size()), vertexRow = uint32_t(store.vertices.size());
  for (size_t k = 0; k < live; ++k) {
    const uint32_t seeds = placement.seed[k], vertices = placement.vertex[k];
    placement.seed[k] = seedRow;
    placement.vertex[k] = vertexRow;
    seedRow += seeds;
    vertexRow += vertices;
  }
  // stageRecordSeeds writes every row placed here (writeSeed, copyChain and the light row).
  store.seeds.resizeForOverwrite(seedRow);
  store.vertices.resizeForOverwrite(vertexRow);
}

void stageRecordSeeds(const StageContext& ctx, const PathQueue& paths, const PathSlotQueue& slots, const HitQueue& hits,
                      const RayQueue& shadowRays, const VertexHistory& history, const SeedPlacement& placement,
                      SeedStore& store, IndexRange range) {
  const VertexQueue& h = *history.vertices;
  VertexQueue& sv = store.vertices;
  for (size_t k = range.begin; k < range.end; ++k) {
    const bool emitted = hitEmitter(slots, k), connected = connectedToLight(slots, shadowRays, k);
    if (!emitted && !connected) continue;
    const uint32_t id = slots.path[k];
    const int32_t vertex = int32_t(history.base + k);
    const uint32_t n = chainLength(h, vertex);
    size_t seedRow = placement.seed[k];
    uint32_t begin = placement.vertex[k];
    if (emitted) {
      // A BSDF sample reached an emitter: the hit vertex is the path's light vertex.
      copyChain(h, vertex, n, sv, begin);
      const size_t last = begin + n - 1;
      const bool environment = sv.kind[last] == kEnvironmentVertex;
      sv.kind[last] = environment ? kEnvironmentVertex : kLightVertex;
      sv.pdfForward[last] = 0;
      // What next-event estimation would have used for this light point.
      const float pLight = environment ? ctx.lights.pdfEnvironment(-sv.ngAt(last))  // its normal faces the scene
                                       : ctx.lights.pdfArea(hits.primID[k], sv.pAt(last - 1), sv.pAt(last), sv.ngAt(last));
      writeSeed(store, seedRow++, paths, id, {false, slots.emitWeight[k], slots.emitAt(k), slots.pLengthHere[k], pLight},
                begin, n);
      begin += n;
    }
    if (connected) {
      copyChain(h, vertex, n, sv, begin);
      // Next-event estimation evaluated the smooth lobes only, so the path is non-specular
      // here, whatever lobe the shade stage then sampled to continue (and wrote into the
      // history's kind: a plastic coat's Dirac lobe, say).
      const size_t last = begin + n - 1;
      sv.kind[last] = kNonSpecularVertex;
      sv.pdfForward[last] = slots.neeBsdfPdf[k];
      VertexQueue::Row light;
      light.p = slots.neeLightAt(k);
      light.ns = light.ng = slots.neeLightNAt(k);
      light.kind = slots.neeLightKind[k];
      light.emitter = slots.neeLightEmitter[k];
      light.parent = int32_t(last);
      sv.setRow(last + 1, light);
      writeSeed(store, seedRow, paths, id,
                {true, slots.neeWeight[k], slots.neeAt(k) / slots.neeWeight[k], slots.pLengthHere[k], slots.neeLightPdf[k]},
                begin, n + 1);
    }
  }
}

}  // namespace erpt
