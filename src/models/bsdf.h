// BSDF evaluation, sampling and pdf in the local shading frame (z = shading normal).
// Conventions follow Mitsuba: `wi` points towards the previous vertex (the camera side),
// `wo` is the sampled direction; eval() returns f(wi, wo) * |cos(wo)| and excludes
// Dirac components, which only sample() produces (with delta = true).
#pragma once

#include "erpt/material.h"

namespace erpt {

struct BsdfSample {
  Vec3 wo;
  Color weight;       // f * |cos(wo)| / pdf  (for a Dirac component: its full weight)
  float pdf = 0;      // solid-angle pdf of the whole BSDF for wo (including lobe choice)
  bool delta = false; // a Dirac component was sampled
  float eta = 1;      // relative IOR crossed (1 for reflection)
};

Color bsdfEval(const Material& m, const SurfaceColors& c, Vec3 wi, Vec3 wo);
// The relative index of refraction crossed from wi's side to wo's: the eta of the BsdfSample
// that goes from wi to wo (1 for reflection, and for materials that do not bend light).
float bsdfEta(const Material& m, Vec3 wi, Vec3 wo);

// Russian roulette's survival probability for a path of throughput `throughput` (with the
// weight of the bounce just sampled) that has crossed refractive boundaries with squared
// relative indices multiplying to etaSquared: Mitsuba 0.6's min(0.95, max(throughput) eta^2).
// The eta^2 undoes the radiance compression of refraction (a BSDF weight of 1/eta^2 on entering
// glass), which would otherwise end paths inside glass objects early and leave the pixels
// behind them black.
inline float russianRouletteSurvival(const Color& throughput, float etaSquared) {
  return std::min(0.95f, maxComponent(throughput) * etaSquared);
}
float bsdfPdf(const Material& m, const SurfaceColors& c, Vec3 wi, Vec3 wo);
// Importance transport (light subpaths): the weight of a sample `s` drawn with bsdfSample from
// wi on the light side, f*(wi, s.wo) |cos(s.wo)| / pdf with the adjoint f*(wi, wo) = f(wo, wi)
// (Veach's thesis, 5.2), shading normals aside. Where the sample took a Dirac lobe this is the
// lobe's own weight with a refraction's radiance scaling undone: importance, unlike radiance,
// is not compressed by (n_i / n_t)^2 (docs/bdpt.md, "Light subpaths").
Color bsdfAdjointWeight(const Material& m, const SurfaceColors& c, Vec3 wi, const BsdfSample& s);
// u1 picks a lobe, (u2, u3) the direction. Returns false when nothing can be sampled.
bool bsdfSample(const Material& m, const SurfaceColors& c, Vec3 wi, float u1, float u2, float u3, BsdfSample& out);

// The Dirac lobe that maps wi to wo (reflection when both lie on the same side, else
// transmission): its value (what sample() returns as weight times `probability`) and the
// probability p_s that sample() picks it. False if the material has no such lobe. Used to
// re-evaluate specular vertices of stored paths (ERPT seeds, density rule 2).
// Off the lobe's direction (cosine to it below kDeltaLobeCosTolerance) the lobe is zero: false.
bool bsdfDeltaLobe(const Material& m, const SurfaceColors& c, Vec3 wi, Vec3 wo, Color& value, float& probability);
// How close (cosine) a stored path's direction must be to a Dirac lobe's to take it: the
// vertices of a path traced along the lobe round to within ~1e-3 rad (ray origins are offset
// from surfaces); 1 - 1e-4 is ~0.014 rad.
constexpr float kDeltaLobeCosTolerance = 1 - 1e-4f;

// The direction a Dirac lobe of `m` sends wi to: mirror reflection, or (transmission) the
// refracted direction of a dielectric / the straight continuation of a thin dielectric.
// False when the material has no such lobe or the refraction is total internal reflection.
// Used by ERPT's mutations to follow a path's specular chain.
bool specularDirection(const Material& m, Vec3 wi, bool reflection, Vec3& wo);
// Factor by which bsdfDeltaLobe's value (radiance transport, wi towards the camera) exceeds
// the same lobe's value for importance transport: (n_i / n_t)^2 for dielectric refraction,
// 1 otherwise. ERPT's caustic perturbation measures paths from the light side.
float deltaRadianceScale(const Material& m, Vec3 wi, Vec3 wo);

// Computes the derived fields of a material (plastic's Fdr and coat sampling weight).
void finalizeMaterial(Material& m);

// Fresnel and microfacet building blocks, exposed for tests.
float fresnelDielectric(float cosThetaI, float eta, float* cosThetaT = nullptr);
Color fresnelConductor(float cosThetaI, Color eta, Color k);
float diffuseFresnelReflectance(float eta);
float microfacetD(MicrofacetKind kind, float alpha, Vec3 m);
float microfacetG1(MicrofacetKind kind, float alpha, Vec3 v, Vec3 m);
Vec3 microfacetSampleNormal(MicrofacetKind kind, float alpha, float u1, float u2);
// Anisotropic: roughness ax along the local x axis (the shading frame's s: dp/du), ay along y.
float microfacetD(MicrofacetKind kind, float ax, float ay, Vec3 m);
float microfacetG1(MicrofacetKind kind, float ax, float ay, Vec3 v, Vec3 m);
Vec3 microfacetSampleNormal(MicrofacetKind kind, float ax, float ay, float u1, float u2);

}  // namespace erpt
