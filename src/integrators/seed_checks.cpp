#include "integrators/seed_checks.h"

#include <cmath>
#include <stdexcept>
#include <vector>

#include "mutations/path_factors.h"

namespace erpt {

bool seedForChains(const SeedStore& store, size_t i, bool excludeDirect) {
  // Eye, one surface vertex, light: a one-bounce path (two vertices: an emitter seen directly).
  return !excludeDirect || store.seeds.vertexCount[i] > 3;
}

namespace {
// A directional light's vertex is a direction, not a point the perturbations can aim at or
// start from: such paths keep their energy where the path tracer found them.
bool litByDirectionalLight(const StepConfig& ctx, const SeedStore& store, size_t i) {
  const int32_t light = store.vertices.emitter[store.seeds.vertexBegin[i] + store.seeds.vertexCount[i] - 1];
  return light >= 0 && ctx.measure.scene.emitters[size_t(light)].kind == EmitterKind::Directional;
}
}  // namespace

void foldSeedTail(const StepConfig& ctx, SeedStore& store, size_t i, int keep) {
  const uint32_t n = store.seeds.vertexCount[i];
  if (n <= uint32_t(keep) || litByDirectionalLight(ctx, store, i)) return;
  std::vector<PathVertex> path(n);
  const size_t begin = store.seeds.vertexBegin[i];
  for (uint32_t j = 0; j < n; ++j) loadPathVertex(store.vertices, begin + j, path[j]);
  const int t = keep - 1;
  PathVertex tail = path[size_t(t)];
  setTailVertexFactor(tail, factors::fixedTail(ctx.measure, path.data(), int(n), t));
  storePathVertex(store.vertices, begin + size_t(t), tail);
  store.seeds.vertexCount[i] = uint32_t(keep);
}

InPlaceReason seedSignatureReason(const StepConfig& ctx, const SeedStore& store, size_t i) {
  if (litByDirectionalLight(ctx, store, i)) return kInPlaceDirectionalLight;
  const uint32_t n = store.seeds.vertexCount[i];
  if (n > uint32_t(kMaxChainVertices)) throw std::logic_error("seedSignatureReason: seed not folded (foldSeedTail)");
  uint8_t kinds[kMaxChainVertices];
  for (uint32_t j = 0; j < n; ++j) kinds[j] = store.vertices.kind[store.seeds.vertexBegin[i] + j];
  // Both choices of the `Mixed` coin.
  const MutationStrategy s = ctx.settings.strategy;
  const bool none = chooseMutation(s, kinds, int(n), 0.0f) == MutationKind::None &&
                    chooseMutation(s, kinds, int(n), 0.999f) == MutationKind::None &&
                    !(ctx.settings.manifold > 0 && manifoldChainEnd(kinds, int(n)) > 0);
  if (!none) return kInPlaceReasonCount;
  return kinds[n - 1] == kTailVertex ? kInPlaceFoldedChain : kInPlaceNoMutation;
}

bool seedHasZeroContribution(const StepConfig& ctx, const SeedStore& store, size_t i) {
  const uint32_t n = store.seeds.vertexCount[i];  // at most kMaxChainVertices (seedSignatureReason)
  PathVertex path[kMaxChainVertices];
  for (uint32_t j = 0; j < n; ++j) loadPathVertex(store.vertices, store.seeds.vertexBegin[i] + j, path[j]);
  return pathHasZeroContribution(ctx, path, int(n), store.seeds.filmX[i], store.seeds.filmY[i]);
}

double depositSeedInPlace(const FilmDensity& density, const SeedStore& store, size_t seed, double energy, Film& film) {
  const Color c = store.contribution(seed);
  const Color deposit = c * float(energy / double(luminance(c)));
  density.splat(store.seeds.filmX[seed], store.seeds.filmY[seed], [&](uint32_t pixel, float w) { film.add(pixel, deposit * w); });
  return luminance(deposit);
}

}  // namespace erpt
