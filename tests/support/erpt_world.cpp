#include "support/erpt_world.h"

#include "stages/chain_step.h"
#include "erpt/render.h"
#include "core/rng.h"

namespace erpt::test {

ErptWorld::ErptWorld(const std::string& sceneFile, int size, int spp, FilterKind filterKind, uint64_t seed,
                     ThinLens lens)
    : scene(loadScene(sceneFile)), width(size), height(size) {
  if (lens.radius > 0) {
    scene.camera.apertureRadius = lens.radius;
    scene.camera.focusDistance = lens.focusDistance;
  }
  tracer = std::make_unique<Tracer>(scene);
  camera = std::make_unique<Camera>(scene.camera, width, height);
  filter = std::make_unique<PixelFilter>(filterKind);
  lights = std::make_unique<LightSampler>(scene);
  density = std::make_unique<FilmDensity>(*filter, width, height);
  RenderSettings s;
  s.integrator = "path";
  s.width = s.height = size;
  s.spp = spp;
  s.seed = seed;
  s.filterSet = true;
  s.filter = filterKind;
  s.seeds = &seeds;
  RenderStats stats;
  render(scene, s, stats);
}

StepConfig ErptWorld::stepContext(MutationStrategy strategy) const {
  StepConfig c{measure(), StepSettings{}};
  c.settings.strategy = strategy;
  return c;
}

std::optional<SurfacePoint> ErptWorld::traceOne(Vec3 origin, Vec3 dir) const {
  RayQueue r;
  HitQueue hits;
  prepareRays(r, 1);
  hits.resize(1);
  setRay(r, 0, origin, dir, 0.0f, std::numeric_limits<float>::infinity());
  tracer->intersect(r, hits, IndexRange{0, 1}, RayCoherence::Incoherent);
  if (hits.geomID[0] == kNoHit || hits.geomID[0] == kRefusedRay) return std::nullopt;
  return surfaceAt(scene, hits.primID[0], hits.u[0], hits.v[0]);
}

int ErptWorld::seedPath(size_t seed, PathVertex* out) const {
  const int n = int(seeds.seeds.vertexCount[seed]);
  for (int j = 0; j < n; ++j) out[j] = loadPathVertex(seeds.vertices, seeds.seeds.vertexBegin[seed] + size_t(j));
  return n;
}

size_t ChainQueues::loadSeeds(const ErptWorld& w, uint32_t chainLength, float energyPerStep, uint64_t keySeed,
                              size_t stride, bool (*keep)(const uint8_t* kinds, int n)) {
  size_t slot = 0;
  uint8_t kinds[kMaxChainVertices];
  for (size_t s = 0; s < w.seeds.size() && slot < chains.size(); s += stride) {
    const uint32_t n = w.seeds.seeds.vertexCount[s];
    if (n > uint32_t(kMaxChainVertices) || !(luminance(w.seeds.contribution(s)) > 0)) continue;
    for (uint32_t j = 0; j < n; ++j) kinds[j] = w.seeds.vertices.kind[w.seeds.seeds.vertexBegin[s] + j];
    if (keep && !keep(kinds, int(n))) continue;
    loadChainFromSeed(chains, chainVertices, slot++, w.seeds, s, streamKey(keySeed, s, 0), chainLength, energyPerStep);
  }
  return slot;
}

void ChainQueues::propose(const ErptWorld& world, const StepConfig& ctx, const ProposalPolicy* chooser) {
  ChainStep{*world.tracer, ctx, nullptr, 256, chooser}.propose(*this);
}

}  // namespace erpt::test
