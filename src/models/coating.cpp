// Mitsuba 0.6's `coating` (a smooth dielectric layer) and `roughcoating` (a rough one) over a
// reflective BSDF, in the spirit of Weidlich and Wilkie's layered surfaces as Mitsuba
// simplifies them: light reflects off the layer's top, or refracts in (Snell's law at the
// mean surface, also under the rough top), meets the coated BSDF, is absorbed along its
// slanted path through the layer (Beer's law, sigma_a times thickness) and refracts out.
// Light reflected back down inside the layer is dropped, an energy loss Mitsuba documents.
// The coated BSDF is evaluated for the refracted directions; its solid angle inside the
// layer is compressed by 1 / eta^2 and the ratio of the cosines outside and inside.
#include "coating.h"

#include <algorithm>
#include <cmath>

namespace erpt {

namespace {

Vec3 flipZ(Vec3 v, float s) { return {v.x, v.y, v.z * s}; }

// A two-sided coating mirrors a back-side wi (and wo) to the front. A one-sided one is, from
// behind, the layer seen from below as Mitsuba has it: the same top reflection, and the
// coated BSDF on its own back side (black unless that BSDF has one).
float twoSidedFlip(const Material& m, Vec3 wi) { return m.twoSided && wi.z < 0 ? -1.0f : 1.0f; }

// Into the layer, on the same side: the direction inside (never total internal reflection
// from outside).
Vec3 refractIn(float eta, Vec3 w) {
  float cosT;
  fresnelDielectric(std::abs(w.z), eta, &cosT);
  const float s = 1 / eta;
  return {w.x * s, w.y * s, std::copysign(std::abs(cosT), w.z)};
}

// Out of the layer: false on total internal reflection.
bool refractOut(float eta, Vec3 w, Vec3& out) {
  float cosT;
  if (fresnelDielectric(-std::abs(w.z), eta, &cosT) >= 1) return false;
  out = {w.x * eta, w.y * eta, std::copysign(std::abs(cosT), w.z)};
  return true;
}

// Beer's law over the two slanted crossings of the layer.
Color absorption(const SurfaceColors& c, Vec3 inside1, Vec3 inside2) {
  const float path = 1 / std::abs(inside1.z) + 1 / std::abs(inside2.z);
  return {std::exp(-c.coatAbsorption.x * path), std::exp(-c.coatAbsorption.y * path), std::exp(-c.coatAbsorption.z * path)};
}

// The probability of sampling the top's reflection: its reflectance at wi, shifted towards
// the top when absorption makes the inside dim (Mitsuba's specular sampling weight).
float topProbability(const Material& m, float cosI) {
  const float r = 1 - coatTransmittance(m, std::abs(cosI)), w = m.specularSamplingWeight;
  const float top = r * w, inside = (1 - r) * (1 - w);
  return top + inside > 0 ? top / (top + inside) : 0.0f;
}

// The coated BSDF seen through the layer (non-Dirac part), f |cos(wo)|.
Color throughLayer(const Material& m, const SurfaceColors& c, Vec3 wi, Vec3 wo) {
  const float eta = m.relativeIOR();
  const Vec3 a = refractIn(eta, wi), b = refractIn(eta, wo);
  const Color f = bsdfEval(m.coated[0], c.part(0), a, b);
  if (isBlack(f)) return f;
  const float crossings = coatTransmittance(m, std::abs(wi.z)) * coatTransmittance(m, std::abs(wo.z));
  return f * absorption(c, a, b) * (crossings * std::abs(wo.z) / (eta * eta * std::abs(b.z)));
}

float throughLayerPdf(const Material& m, const SurfaceColors& c, Vec3 wi, Vec3 wo) {
  const float eta = m.relativeIOR();
  const Vec3 a = refractIn(eta, wi), b = refractIn(eta, wo);
  return bsdfPdf(m.coated[0], c.part(0), a, b) * std::abs(wo.z) / (eta * eta * std::abs(b.z));
}

// The rough top's reflection (isotropic microfacets, dielectric Fresnel), on either side:
// the interface is the same seen from below.
Color roughTop(const Material& m, const SurfaceColors& c, Vec3 wi, Vec3 wo) {
  const float side = wi.z < 0 ? -1.0f : 1.0f;
  const Vec3 i = flipZ(wi, side), o = flipZ(wo, side), h = normalize(i + o);
  const float d = microfacetD(m.distribution, m.alpha, h);
  if (!(d > 0)) return Color(0.0f);
  const float g = microfacetG1(m.distribution, m.alpha, i, h) * microfacetG1(m.distribution, m.alpha, o, h);
  return c.specularReflectance * (fresnelDielectric(dot(i, h), m.relativeIOR()) * d * g / (4 * i.z));
}

float roughTopPdf(const Material& m, Vec3 wi, Vec3 wo) {
  const float side = wi.z < 0 ? -1.0f : 1.0f;
  const Vec3 i = flipZ(wi, side), o = flipZ(wo, side), h = normalize(i + o);
  const float cosOH = dot(o, h);
  return cosOH > 0 ? microfacetD(m.distribution, m.alpha, h) * h.z / (4 * cosOH) : 0.0f;
}

// eval and pdf once a two-sided coating's flip is applied.
Color evalLayered(const Material& m, const SurfaceColors& c, Vec3 wi, Vec3 wo) {
  if (!(wi.z * wo.z > 0)) return Color(0.0f);  // the coated BSDFs only reflect
  Color f = throughLayer(m, c, wi, wo);
  if (m.kind == BsdfKind::RoughCoating) f += roughTop(m, c, wi, wo);
  return f;
}

float pdfLayered(const Material& m, const SurfaceColors& c, Vec3 wi, Vec3 wo) {
  if (!(wi.z * wo.z > 0)) return 0.0f;
  const float top = topProbability(m, wi.z);
  float p = (1 - top) * throughLayerPdf(m, c, wi, wo);
  if (m.kind == BsdfKind::RoughCoating) p += top * roughTopPdf(m, wi, wo);
  return p;
}

}  // namespace

Color coatingEval(const Material& m, const SurfaceColors& c, Vec3 wi, Vec3 wo) {
  const float flip = twoSidedFlip(m, wi);
  return evalLayered(m, c, flipZ(wi, flip), flipZ(wo, flip));
}

float coatingPdf(const Material& m, const SurfaceColors& c, Vec3 wi, Vec3 wo) {
  const float flip = twoSidedFlip(m, wi);
  return pdfLayered(m, c, flipZ(wi, flip), flipZ(wo, flip));
}

bool coatingSample(const Material& m, const SurfaceColors& c, Vec3 wiGiven, float u1, float u2, float u3, BsdfSample& s) {
  const float flip = twoSidedFlip(m, wiGiven);
  const Vec3 wi = flipZ(wiGiven, flip);
  if (wi.z == 0) return false;
  const float top = topProbability(m, wi.z);
  if (u1 < top) {
    if (m.kind == BsdfKind::Coating) {
      s.wo = flipZ({-wi.x, -wi.y, wi.z}, flip);
      s.weight = c.specularReflectance * ((1 - coatTransmittance(m, std::abs(wi.z))) / top);
      s.pdf = top;
      s.delta = true;
      return true;
    }
    const float side = wi.z < 0 ? -1.0f : 1.0f;
    const Vec3 o = reflect(flipZ(wi, side), microfacetSampleNormal(m.distribution, m.alpha, u2, u3));
    if (o.z <= 0) return false;
    s.wo = flipZ(o, side);
  } else {
    const float eta = m.relativeIOR();
    const Vec3 a = refractIn(eta, wi);
    BsdfSample inner;
    if (!bsdfSample(m.coated[0], c.part(0), a, std::min((u1 - top) / (1 - top), 0x1.fffffep-1f), u2, u3, inner)) return false;
    if (!(inner.wo.z * a.z > 0) || !refractOut(eta, inner.wo, s.wo)) return false;
    if (inner.delta) {
      // A Dirac lobe of the coated BSDF (a mirror) stays one outside: its weight through the
      // layer, its probability times that of going inside.
      const float crossings = coatTransmittance(m, std::abs(wi.z)) * coatTransmittance(m, std::abs(s.wo.z));
      s.weight = inner.weight * absorption(c, a, inner.wo) * (crossings / (1 - top));
      s.pdf = inner.pdf * (1 - top);
      s.delta = true;
      s.wo = flipZ(s.wo, flip);
      return true;
    }
  }
  s.pdf = pdfLayered(m, c, wi, s.wo);
  if (!(s.pdf > 0)) return false;
  s.weight = evalLayered(m, c, wi, s.wo) / s.pdf;
  s.wo = flipZ(s.wo, flip);
  return true;
}

bool coatingDeltaLobe(const Material& m, const SurfaceColors& c, Vec3 wiGiven, Vec3 woGiven, Color& value,
                      float& probability) {
  const float flip = twoSidedFlip(m, wiGiven);
  const Vec3 wi = flipZ(wiGiven, flip), wo = flipZ(woGiven, flip);
  value = Color(0.0f);
  probability = 0;
  if (!(wi.z * wo.z > 0)) return false;
  const float top = topProbability(m, wi.z);
  if (m.kind == BsdfKind::Coating) {
    value = c.specularReflectance * (1 - coatTransmittance(m, std::abs(wi.z)));
    probability = top;
  }
  const float eta = m.relativeIOR();
  const Vec3 a = refractIn(eta, wi), b = refractIn(eta, wo);
  Color inner;
  float innerProbability;
  if (bsdfDeltaLobe(m.coated[0], c.part(0), a, b, inner, innerProbability)) {
    const float crossings = coatTransmittance(m, std::abs(wi.z)) * coatTransmittance(m, std::abs(wo.z));
    value += inner * absorption(c, a, b) * crossings;
    probability += innerProbability * (1 - top);
  }
  return probability > 0;
}

}  // namespace erpt
