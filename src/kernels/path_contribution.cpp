// A path's contribution f in the measure of each mutation (docs/erpt-acceptance.md). The
// acceptance probability of a mutation is the ratio of these for the proposal and the
// current path: the mutations' own sampling densities are symmetric in these measures and
// cancel.
#include <algorithm>
#include <cmath>

#include "erpt/bsdf.h"
#include "erpt/erpt_path.h"

namespace erpt {

namespace {

struct LocalBsdf {
  const Material& material;
  SurfaceColors colors;
  Frame frame;
};

LocalBsdf bsdfAt(const MeasureContext& c, const PathVertex& v) {
  return {c.scene.materials[size_t(v.material)], c.scene.surfaceColors(v.material, v.u, v.v), Frame(v.ns)};
}

// f(wi, wo) |cos(wo)| of a non-specular vertex (wi towards the camera side, world space).
Color evalAt(const MeasureContext& c, const PathVertex& v, Vec3 wi, Vec3 wo) {
  if (v.material < 0) return Color(0.0f);
  LocalBsdf b = bsdfAt(c, v);
  return bsdfEval(b.material, b.colors, b.frame.toLocal(wi), b.frame.toLocal(wo));
}

// Value of the Dirac lobe taking wi to wo at a specular vertex (radiance transport); black if
// the material has no such lobe. `adjoint`: the importance-transport value instead.
Color specularAt(const MeasureContext& c, const PathVertex& v, Vec3 wi, Vec3 wo, bool adjoint) {
  if (v.material < 0) return Color(0.0f);
  LocalBsdf b = bsdfAt(c, v);
  Vec3 li = b.frame.toLocal(wi), lo = b.frame.toLocal(wo);
  Color value;
  float probability;
  if (!bsdfDeltaLobe(b.material, b.colors, li, lo, value, probability)) return Color(0.0f);
  return adjoint ? value / deltaRadianceScale(b.material, li, lo) : value;
}

// Radiance (area light, environment) or intensity (point light) a light vertex sends along w.
Color emittedAlong(const MeasureContext& c, const PathVertex& light, Vec3 w) {
  if (light.emitter < 0) return Color(0.0f);
  const Emitter& e = c.scene.emitters[size_t(light.emitter)];
  if (e.kind == EmitterKind::Area && dot(light.ng, w) <= 0) return Color(0.0f);  // one-sided
  return e.radiance;
}

bool isPointLight(const MeasureContext& c, const PathVertex& v) {
  return v.kind == kLightVertex && v.emitter >= 0 && c.scene.emitters[size_t(v.emitter)].kind == EmitterKind::Point;
}

// Solid angle at `from` per unit area at `to` (rule 3's geometry term without the cosine at
// `from`, which the BSDF factor carries): |cos_g(to)| / d^2; a point light has no area (1 /
// d^2), the environment is a direction (1).
float areaFactor(const MeasureContext& c, const PathVertex& from, const PathVertex& to) {
  if (to.kind == kEnvironmentVertex) return 1.0f;
  const Vec3 d = to.p - from.p;
  const float dist2 = dot(d, d);
  if (isPointLight(c, to)) return 1.0f / dist2;
  return std::abs(dot(to.ng, d)) / (dist2 * std::sqrt(dist2));
}

// The vertices from `first` on, which a mutation leaves where they are (area measure, with
// their incoming directions): a constant factor of f for the mutation, so it cancels in the
// acceptance ratio. It is still multiplied in: its colour is part of the path's colour, which
// deposits carry, and with it f is the whole density in the mutation's measure, so the f of
// different mutations can be compared (tests/erpt/erpt_measure_test.cpp).
Color fixedTail(const MeasureContext& c, const PathVertex* path, int n, int first) {
  Color f(1.0f);
  for (int k = first; k < n; ++k) {
    const PathVertex& v = path[k];
    const Vec3 toPrev = directionBetween(v, path[k - 1]);
    f *= areaFactor(c, path[k - 1], v);
    if (v.kind == kLightVertex || v.kind == kEnvironmentVertex) return f * emittedAlong(c, v, toPrev);
    if (k + 1 >= n) return Color(0.0f);
    const Vec3 toNext = directionBetween(v, path[k + 1]);
    f *= v.kind == kSpecularVertex ? specularAt(c, v, toPrev, toNext, false) : evalAt(c, v, toPrev, toNext);
  }
  return Color(0.0f);
}

}  // namespace

// The tail from `first` on: from the cache when it holds it, else computed (and cached).
Color tailFrom(const MeasureContext& c, const PathVertex* path, int n, int first, FixedTail* cache) {
  if (cache && cache->known) return cache->value;
  const Color t = fixedTail(c, path, n, first);
  if (cache) *cache = FixedTail{t, true};
  return t;
}

int lensConnectionTarget(const uint8_t* kinds, int n) {
  for (int j = 1; j < n; ++j) {
    if (kinds[j] == kLightVertex || kinds[j] == kEnvironmentVertex) return -1;  // reached by tracing
    if (kinds[j] == kSpecularVertex || (j + 1 < n && kinds[j + 1] == kSpecularVertex)) continue;
    return j + 1;
  }
  return -1;
}

int tailStart(MutationKind kind, const uint8_t* kinds, int n) {
  int last = -1;  // the last vertex whose factor a mutation changes
  if (kind == MutationKind::Lens) last = lensConnectionTarget(kinds, n);
  if (kind == MutationKind::Caustic) last = causticSource(kinds, n);
  return last < 0 ? n : std::min(n, last + 1);
}

Color lensContribution(const MeasureContext& c, const PathVertex* path, int n, float filmX, float filmY,
                       FixedTail* tail) {
  Color f(c.film.density(filmX, filmY));
  if (isBlack(f)) return f;
  for (int j = 1; j < n; ++j) {
    const PathVertex& v = path[j];
    const Vec3 toPrev = directionBetween(v, path[j - 1]);
    // Reached by tracing: a light or the environment ends the walk (solid-angle measure).
    if (v.kind == kLightVertex || v.kind == kEnvironmentVertex) return f * emittedAlong(c, v, toPrev);
    if (j + 1 >= n) return Color(0.0f);
    const Vec3 toNext = directionBetween(v, path[j + 1]);
    if (v.kind == kSpecularVertex) {
      f *= specularAt(c, v, toPrev, toNext, false);
      continue;
    }
    f *= evalAt(c, v, toPrev, toNext);
    if (path[j + 1].kind == kSpecularVertex) continue;  // perturbed direction: solid angle
    // Connection to the fixed vertex t = j + 1 (area measure), which keeps its outgoing
    // direction but sees a new incoming one; then the rest of the path.
    const PathVertex& t = path[j + 1];
    f *= areaFactor(c, v, t);
    if (t.kind == kLightVertex || t.kind == kEnvironmentVertex) return f * emittedAlong(c, t, -toNext);
    if (j + 2 >= n) return Color(0.0f);
    f *= evalAt(c, t, -toNext, directionBetween(t, path[j + 2]));
    return f * tailFrom(c, path, n, j + 2, tail);
  }
  return Color(0.0f);
}

Color causticContribution(const MeasureContext& c, const PathVertex* path, int n, float filmX, float filmY,
                          FixedTail* tail) {
  uint8_t kinds[kMaxChainVertices];
  if (n > kMaxChainVertices) return Color(0.0f);
  for (int j = 0; j < n; ++j) kinds[j] = path[j].kind;
  const int s = causticSource(kinds, n);
  if (s < 0) return Color(0.0f);
  const float h = c.film.density(filmX, filmY);
  const PathVertex& v1 = path[1];
  const Vec3 toEye = c.camera.position() - v1.p;
  const float dist2 = dot(toEye, toEye);
  const Vec3 wEye = toEye / std::sqrt(dist2);
  const float cosAxis = c.camera.cosToAxis(-wEye);
  if (!(h > 0) || !(cosAxis > 0)) return Color(0.0f);
  // Film area (pixels^2) per unit area at v1 (density rule 5), then v1's BSDF: the cosine towards the
  // light side is shading-normal; the geometric one cancels against the specular chain's
  // etendue (docs/erpt-acceptance.md).
  const Vec3 toV2 = directionBetween(v1, path[2]);
  const float cosG1 = std::abs(dot(v1.ng, toV2));
  if (!(cosG1 > 0)) return Color(0.0f);
  const float pixelScale = c.camera.pixelsPerPlaneUnit();
  Color f = evalAt(c, v1, wEye, toV2) * (h * pixelScale * pixelScale * std::abs(dot(v1.ng, wEye)) /
                                         (dist2 * cosAxis * cosAxis * cosAxis * cosG1));
  for (int j = 2; j < s; ++j)
    f *= specularAt(c, path[j], directionBetween(path[j], path[j - 1]), directionBetween(path[j], path[j + 1]), true);
  const PathVertex& src = path[s];
  const Vec3 ws = directionBetween(src, path[s - 1]);
  if (isPointLight(c, src)) return f * emittedAlong(c, src, ws);
  const float cosS = std::abs(dot(src.ng, ws));
  if (src.kind == kLightVertex) return f * emittedAlong(c, src, ws) * cosS;
  if (s + 1 >= n) return Color(0.0f);
  return f * evalAt(c, src, ws, directionBetween(src, path[s + 1])) * cosS * tailFrom(c, path, n, s + 1, tail);
}

Color contributionFor(MutationKind kind, const MeasureContext& c, const PathVertex* path, int n, float filmX,
                      float filmY, FixedTail* tail) {
  switch (kind) {
    case MutationKind::Lens: return lensContribution(c, path, n, filmX, filmY, tail);
    case MutationKind::Caustic: return causticContribution(c, path, n, filmX, filmY, tail);
    default: return Color(0.0f);
  }
}

}  // namespace erpt
