// Path contribution factors shared by the mutations' measures (path_factors.h).
#include "path_factors.h"

#include <cmath>

#include "models/bsdf.h"

namespace erpt::factors {

namespace {

struct LocalBsdf {
  const Material& material;
  SurfaceColors colors;
  Frame frame;
};

LocalBsdf bsdfAt(const MeasureContext& c, const PathVertex& v) {
  const Material& m = c.scene.materials[size_t(v.material)];
  // An anisotropic BSDF needs the frame the path was shaded in (its s along dp/du); any frame
  // around the normal serves an isotropic one.
  return {m, c.scene.surfaceColors(v.material, v.u, v.v), m.anisotropic() ? Frame::turned(v.ns, v.tangentAngle) : Frame(v.ns)};
}

}  // namespace

// f(wi, wo) |cos(wo)| of a non-specular vertex (wi towards the camera side, world space).
Color evalAt(const MeasureContext& c, const PathVertex& v, Vec3 wi, Vec3 wo) {
  if (v.material < 0) return Color(0.0f);
  LocalBsdf b = bsdfAt(c, v);
  return bsdfEval(b.material, b.colors, b.frame.toLocal(wi), b.frame.toLocal(wo));
}

float pdfAt(const MeasureContext& c, const PathVertex& v, Vec3 wi, Vec3 wo) {
  if (v.material < 0) return 0.0f;
  LocalBsdf b = bsdfAt(c, v);
  return bsdfPdf(b.material, b.colors, b.frame.toLocal(wi), b.frame.toLocal(wo));
}

bool sampleAt(const MeasureContext& c, PathVertex& v, Vec3 wi, float u1, float u2, float u3, Vec3& wo) {
  if (v.material < 0) return false;
  LocalBsdf b = bsdfAt(c, v);
  BsdfSample s;
  if (!bsdfSample(b.material, b.colors, b.frame.toLocal(wi), u1, u2, u3, s) || !(s.pdf > 0) || isBlack(s.weight)) return false;
  v.kind = s.delta ? kSpecularVertex : kNonSpecularVertex;
  wo = b.frame.toWorld(s.wo);
  return true;
}

float etaAt(const MeasureContext& c, const PathVertex& v, Vec3 wi, Vec3 wo) {
  if (v.material < 0) return 1.0f;
  LocalBsdf b = bsdfAt(c, v);
  return bsdfEta(b.material, b.frame.toLocal(wi), b.frame.toLocal(wo));
}

bool specularLobeAt(const MeasureContext& c, const PathVertex& v, Vec3 wi, Vec3 wo, Color& value, float& probability) {
  if (v.material < 0) return false;
  LocalBsdf b = bsdfAt(c, v);
  return bsdfDeltaLobe(b.material, b.colors, b.frame.toLocal(wi), b.frame.toLocal(wo), value, probability);
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
  if (e.kind == EmitterKind::Point) return e.radiance * e.falloff(w);        // a spot's cone
  if (e.kind == EmitterKind::Constant) return e.environmentRadiance(-w);     // w leaves the environment
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
// different mutations can be compared (tests/mutations/erpt_measure_test.cpp).
Color fixedTail(const MeasureContext& c, const PathVertex* path, int n, int first) {
  Color f(1.0f);
  for (int k = first; k < n; ++k) {
    const PathVertex& v = path[k];
    if (v.kind == kTailVertex) return f * tailVertexFactor(v);  // the folded rest, its area factor included
    const Vec3 toPrev = directionBetween(v, path[k - 1]);
    f *= areaFactor(c, path[k - 1], v);
    if (v.kind == kLightVertex || v.kind == kEnvironmentVertex) return f * emittedAlong(c, v, toPrev);
    if (k + 1 >= n) return Color(0.0f);
    const Vec3 toNext = directionBetween(v, path[k + 1]);
    f *= v.kind == kSpecularVertex ? specularAt(c, v, toPrev, toNext, false) : evalAt(c, v, toPrev, toNext);
  }
  return Color(0.0f);
}

// The tail from `first` on: from the cache when it holds it, else computed (and cached).
Color tailFrom(const MeasureContext& c, const PathVertex* path, int n, int first, FixedTail* cache) {
  if (cache && cache->known) return cache->value;
  const Color t = fixedTail(c, path, n, first);
  if (cache) *cache = FixedTail{t, true};
  return t;
}

}  // namespace erpt::factors
