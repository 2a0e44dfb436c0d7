// BDPT as ERPT's seed sampler: every contribution that arrived becomes a seed, a complete path
// in the seed store's layout (eye first, light last; the vertex kinds ERPT's mutations read)
// with its MIS-weighted energy at its film position (docs/bdpt.md, "Seeds").
#include <algorithm>
#include <cmath>

#include "kernels/bdpt_vertex.h"
#include "stages/bdpt_stages.h"

namespace erpt {

namespace {
// A stand-in distance for vertices at infinity, as the path tracer's seeds use.
constexpr float kFarAway = 1e6f;

VertexQueue::Row seedVertex(const BdptVertex& v) {
  VertexQueue::Row r;
  r.p = v.p;
  r.ns = v.ns;
  r.tangentAngle = v.tangentAngle;
  r.ng = v.ng;
  r.material = v.material;
  r.u = v.u;
  r.v = v.v;
  r.kind = v.kind;
  r.emitter = v.emitter;
  return r;
}

// The light end of a seed, after vertex `before`: area and point lights keep their point;
// the environment stands far along its direction, facing the scene (as the path tracer's seeds
// have it); a directional light likewise, as a light vertex (ERPT keeps such seeds in place).
VertexQueue::Row seedLightVertex(const Scene& scene, const BdptVertex& v, const VertexQueue::Row& before,
                                 bool keepMaterial) {
  VertexQueue::Row r = seedVertex(v);
  if (!keepMaterial) r.material = -1;
  if (atInfinity(v)) {
    const Vec3 toward = v.ng;
    r.p = before.p + toward * kFarAway;
    const bool directional = scene.emitters[size_t(v.emitter)].kind == EmitterKind::Directional;
    r.ns = r.ng = -toward;
    r.kind = directional ? kLightVertex : kEnvironmentVertex;
  } else {
    r.ns = r.ng;
    r.kind = kLightVertex;
  }
  return r;
}

const BdptVertexQueue& queueOf(const BdptSubpaths& paths, const BdptConnectScratch& scratch, int32_t v) {
  return v >= 0 ? paths.vertices : scratch.extra;
}
size_t rowOf(int32_t v) { return v >= 0 ? size_t(v) : size_t(-1 - v); }
}  // namespace

void stageBdptRecordSeeds(const BdptContext& ctx, const BdptSubpaths& paths, const BdptConnectScratch& scratch,
                          const BdptConnectionQueue& connections, const RayQueue& rays, size_t n, size_t firstSample,
                          SeedStore& store) {
  const Scene& scene = ctx.stage.scene;
  std::vector<BdptVertex> cameraPart, lightPart;
  auto recorded = [&](size_t c) {
    return rays.tfar[c] >= 0 && !isBlack(connections.valueAt(c)) && isFinite(connections.valueAt(c));
  };
  // Room for every seed first (the queues' columns grow once, not once per seed).
  size_t seedCount = 0, vertexCount = 0;
  for (size_t c = 0; c < n; ++c) {
    if (!recorded(c)) continue;
    ++seedCount;
    vertexCount += size_t(connections.s[c]) + connections.t[c];
  }
  size_t seedRow = store.seeds.size(), vertexRow = store.vertices.size();
  store.seeds.resize(seedRow + seedCount);
  store.vertices.resize(vertexRow + vertexCount);
  for (size_t c = 0; c < n; ++c) {
    if (!recorded(c)) continue;  // occluded, or nothing
    const Color value = connections.valueAt(c);
    const int s = connections.s[c], t = connections.t[c];
    const uint32_t sample = connections.sample[c];
    // Camera part, eye first; light part from the connection's end to the light.
    cameraPart.clear();
    const int32_t cameraEnd = connections.cameraVertex[c];
    if (cameraEnd < 0) {
      cameraPart.push_back(scratch.extra.row(rowOf(cameraEnd)));
    } else {
      for (int32_t v = cameraEnd; v >= 0; v = paths.vertices.parent[size_t(v)]) cameraPart.push_back(paths.vertices.row(size_t(v)));
      std::reverse(cameraPart.begin(), cameraPart.end());
    }
    lightPart.clear();
    if (s > 0) {
      const int32_t lightEnd = connections.lightVertex[c];
      const BdptVertexQueue& q = queueOf(paths, scratch, lightEnd);
      for (int32_t v = lightEnd;;) {
        lightPart.push_back(q.row(rowOf(v)));
        if (v < 0 || paths.vertices.parent[size_t(v)] < 0) break;
        v = paths.vertices.parent[size_t(v)];
      }
    }
    const size_t begin = vertexRow;
    const size_t count = cameraPart.size() + lightPart.size();  // s + t
    vertexRow += count;
    size_t at = begin;
    auto put = [&](VertexQueue::Row r) {
      r.parent = at == begin ? -1 : int32_t(at - 1);
      r.pdfForward = 0;
      store.vertices.setRow(at++, r);
    };
    for (size_t j = 0; j < cameraPart.size(); ++j) {
      const bool last = j + 1 == cameraPart.size();
      if (last && s == 0) {
        put(seedLightVertex(scene, cameraPart[j], store.vertices.row(at - 1), true));
        continue;
      }
      VertexQueue::Row r = seedVertex(cameraPart[j]);
      if (last && j > 0) r.kind = kNonSpecularVertex;  // the connection evaluated its smooth lobes
      put(r);
    }
    for (size_t j = 0; j < lightPart.size(); ++j) {
      if (j + 1 == lightPart.size()) {
        put(seedLightVertex(scene, lightPart[j], store.vertices.row(at - 1), false));
        continue;
      }
      VertexQueue::Row r = seedVertex(lightPart[j]);
      if (j == 0) r.kind = kNonSpecularVertex;
      put(r);
    }
    SeedQueue::Row seed;
    if (t == 1) {
      const float fx = connections.filmX[c], fy = connections.filmY[c];
      seed.filmX = fx;
      seed.filmY = fy;
      seed.pixel = uint32_t(std::min(int(fy), ctx.height - 1)) * uint32_t(ctx.stage.width) +
                   uint32_t(std::min(int(fx), ctx.stage.width - 1));
    } else {
      seed.filmX = paths.filmX[sample];
      seed.filmY = paths.filmY[sample];
      seed.pixel = paths.pixel[sample];
    }
    seed.path = uint32_t(firstSample + sample);
    seed.explicitLight = uint8_t(std::min(s, 255));  // the strategy: names the path within its sample
    const float w = connections.misWeight[c];
    seed.misWeight = w > 0 ? w : 1.0f;
    seed.estimate = w > 0 ? value / w : value;
    seed.pLength = 1;
    seed.pLight = 0;
    seed.vertexBegin = uint32_t(begin);
    seed.vertexCount = uint32_t(count);
    store.seeds.setRow(seedRow++, seed);
  }
}

}  // namespace erpt
