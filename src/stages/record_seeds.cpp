// Seed recording: turns this bounce's contributions into complete seed paths. Runs on one
// thread in slot order, so the seed store's order is fixed; it only runs when ERPT (or a
// test) asks for seeds.
#include <algorithm>
#include <vector>

#include "stages/stages.h"

namespace erpt {

namespace {

// Appends the history chain ending at `last` (eye first) to the store; returns the index of
// the first appended vertex.
uint32_t copyChain(const VertexQueue& history, int32_t last, VertexQueue& out, std::vector<int32_t>& scratch) {
  scratch.clear();
  for (int32_t v = last; v >= 0; v = history.parent[v]) scratch.push_back(v);
  std::reverse(scratch.begin(), scratch.end());
  uint32_t begin = uint32_t(out.size());
  out.resize(begin + scratch.size());
  for (size_t j = 0; j < scratch.size(); ++j) {
    out.copyRow(begin + j, history, size_t(scratch[j]));
    out.parent[begin + j] = j == 0 ? -1 : int32_t(begin + j - 1);
  }
  return begin;
}

void appendSeed(SeedStore& store, const PathQueue& paths, uint32_t id, bool explicitLight, float weight, Color estimate,
                float pLength, float pLight, uint32_t begin) {
  SeedQueue::Row seed;
  seed.pixel = paths.pixel[id];
  seed.path = paths.runIndex[id];
  seed.filmX = paths.filmX[id];
  seed.filmY = paths.filmY[id];
  seed.explicitLight = explicitLight;
  seed.misWeight = weight;
  seed.estimate = estimate;
  seed.pLength = pLength;
  seed.pLight = pLight;
  seed.vertexBegin = begin;
  seed.vertexCount = uint32_t(store.vertices.size()) - begin;
  const size_t i = store.seeds.size();
  store.seeds.resize(i + 1);
  store.seeds.setRow(i, seed);
}

}  // namespace

void stageRecordSeeds(const StageContext& ctx, const PathQueue& paths, const PathSlotQueue& slots, const HitQueue& hits,
                      const RayQueue& shadowRays, const VertexHistory& history, size_t live, SeedStore& store) {
  std::vector<int32_t> scratch;
  const VertexQueue& h = *history.vertices;
  for (size_t k = 0; k < live; ++k) {
    const uint32_t id = slots.path[k];
    const int32_t vertex = int32_t(history.base + k);
    if (slots.emitWeight[k] > 0) {
      // A BSDF sample reached an emitter: the hit vertex is the path's light vertex.
      uint32_t begin = copyChain(h, vertex, store.vertices, scratch);
      size_t last = store.vertices.size() - 1;
      bool environment = store.vertices.kind[last] == kEnvironmentVertex;
      store.vertices.kind[last] = environment ? kEnvironmentVertex : kLightVertex;
      store.vertices.pdfForward[last] = 0;
      // What next-event estimation would have used for this light point.
      const VertexQueue& sv = store.vertices;
      float pLight = environment ? ctx.lights.pdfEnvironment(-sv.ngAt(last))  // its normal faces the scene
                                 : ctx.lights.pdfArea(hits.primID[k], sv.pAt(last - 1), sv.pAt(last), sv.ngAt(last));
      appendSeed(store, paths, id, false, slots.emitWeight[k], slots.emitAt(k), slots.pLengthHere[k], pLight, begin);
    }
    if (slots.neeWeight[k] > 0 && shadowRays.tfar[k] >= 0) {
      uint32_t begin = copyChain(h, vertex, store.vertices, scratch);
      // Next-event estimation evaluated the smooth lobes only, so the path is non-specular
      // here, whatever lobe the shade stage then sampled to continue (and wrote into the
      // history's kind: a plastic coat's Dirac lobe, say).
      store.vertices.kind[store.vertices.size() - 1] = kNonSpecularVertex;
      store.vertices.pdfForward[store.vertices.size() - 1] = slots.neeBsdfPdf[k];
      const size_t l = store.vertices.size();
      VertexQueue::Row light;
      light.p = slots.neeLightAt(k);
      light.ns = light.ng = slots.neeLightNAt(k);
      light.kind = slots.neeLightKind[k];
      light.emitter = slots.neeLightEmitter[k];
      light.parent = int32_t(l - 1);
      store.vertices.resize(l + 1);
      store.vertices.setRow(l, light);
      appendSeed(store, paths, id, true, slots.neeWeight[k], slots.neeAt(k) / slots.neeWeight[k], slots.pLengthHere[k],
                 slots.neeLightPdf[k], begin);
    }
  }
}

}  // namespace erpt
