#include "integrators/seed_checks.h"

#include <cmath>

namespace erpt {

bool seedForChains(const SeedStore& store, size_t i, bool excludeDirect) {
  // Eye, one surface vertex, light: a one-bounce path (two vertices: an emitter seen directly).
  return !excludeDirect || store.seeds.vertexCount[i] > 3;
}

InPlaceReason seedSignatureReason(const StepConfig& ctx, const SeedStore& store, size_t i) {
  const uint32_t n = store.seeds.vertexCount[i];
  if (n > uint32_t(kMaxChainVertices)) return kInPlaceTooLong;
  uint8_t kinds[kMaxChainVertices];
  for (uint32_t j = 0; j < n; ++j) kinds[j] = store.vertices.kind[store.seeds.vertexBegin[i] + j];
  // A directional light's vertex is a direction, not a point the perturbations can aim at or
  // start from: such paths keep their energy where the path tracer found them.
  const int32_t light = store.vertices.emitter[store.seeds.vertexBegin[i] + n - 1];
  if (light >= 0 && ctx.measure.scene.emitters[size_t(light)].kind == EmitterKind::Directional)
    return kInPlaceDirectionalLight;
  // Both choices of the `Mixed` coin.
  const MutationStrategy s = ctx.settings.strategy;
  const bool none = chooseMutation(s, kinds, int(n), 0.0f) == MutationKind::None &&
                    chooseMutation(s, kinds, int(n), 0.999f) == MutationKind::None;
  return none ? kInPlaceNoMutation : kInPlaceReasonCount;
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
