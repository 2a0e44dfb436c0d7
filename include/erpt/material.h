// Materials as plain data (one struct for every BSDF kind; the kind selects the code path).
// Textured colours are resolved to constants at a hit before the BSDF is evaluated.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "erpt/texture.h"

namespace erpt {

enum class BsdfKind { Diffuse, Conductor, RoughConductor, Dielectric, ThinDielectric, Plastic, RoughPlastic, RoughDielectric,
                      Phong, Blend, Ward, Coating, RoughCoating };
// Ward's normalisation variants, as Mitsuba 0.6 names them (`variant`).
enum class WardVariant { Ward, WardDuer, Balanced };
enum class MicrofacetKind { Beckmann, GGX };
// A wrapper that perturbs the shading normal at every hit (shading_frames.cpp): `normalmap`
// (a tangent-space normal texture, Mitsuba 3) or `bumpmap` (a height texture, both dialects).
enum class ShadingMap { None, Normal, Bump };
// The most non-blend BSDFs one blend tree (nested blendbsdf / mixturebsdf) may hold: the
// size of SurfaceColors' per-part colours.
constexpr int kMaxBlendLeaves = 8;

struct Material {
  std::string name;  // the XML id, or the plugin type when anonymous
  BsdfKind kind = BsdfKind::Diffuse;
  // Wrapped in `twosided`: the back side behaves like the front. Without it, reflective
  // BSDFs are black from behind (as in Mitsuba); dielectrics are two-sided by nature.
  bool twoSided = false;
  ColorParam reflectance{Color(0.5f)};            // diffuse / plastic's diffuse layer / phong's diffuse lobe
  ColorParam specularReflectance{Color(1.0f)};    // conductor, dielectric, plastic coat, phong's specular lobe
  ColorParam specularTransmittance{Color(1.0f)};  // dielectric, thindielectric
  Color eta{0.0f}, k{1.0f};                       // conductor (default: a perfect mirror)
  float intIOR = 1.5046f, extIOR = 1.000277f;     // dielectric / plastic (Mitsuba's defaults)
  MicrofacetKind distribution = MicrofacetKind::Beckmann;
  float alpha = 0.1f;    // microfacet roughness; anisotropic: along dp/du (Mitsuba's alpha_u)
  float alphaV = -1;     // anisotropic: the roughness along dp/dv; < 0: isotropic (alpha)
  float exponent = 30;  // phong: the specular lobe's exponent
  WardVariant wardVariant = WardVariant::Balanced;  // ward (its roughness: alpha, alphaV)
  bool nonlinear = false;  // plastic: Mitsuba's `nonlinear` internal scattering model
  // Wrapped in `mask`: a cut-out. Rays pass through where the opacity (its channels' mean) is
  // below 0.5, in every integrator (an Embree intersection filter); Mitsuba blends partial
  // opacities stochastically, which the loader warns about.
  bool masked = false;
  ColorParam opacity{Color(1.0f)};
  ShadingMap shadingMap = ShadingMap::None;
  int shadingTexture = -1;  // index into Scene::textures: the normals (raw RGB) or the heights
  float bumpScale = 1;      // bumpmap: heights are multiplied by this (Mitsuba 3's `scale`)
  // Derived when the scene is finalized:
  float fdrInternal = 0;             // plastic: diffuse Fresnel reflectance seen from inside
  float specularSamplingWeight = 0;  // plastic, coatings: share of samples given to the coat; phong: to the specular lobe
  std::vector<float> coatTransmittance;  // roughplastic, roughcoating: 1 - coat albedo over cos(theta) in [0, 1]
  // blendbsdf: (1 - w) f_0 + w f_1 with w = blendWeight (its channels' mean, in [0, 1]); the
  // two parts are whole materials of their own, blends too (mixturebsdf loads as a chain of
  // blends), with at most kMaxBlendLeaves non-blend BSDFs in the whole tree.
  std::vector<Material> blendParts;
  ColorParam blendWeight{Color(0.5f)};
  // coating, roughcoating (Mitsuba 0.6): a dielectric layer (intIOR / extIOR; roughcoating:
  // distribution, alpha) over `coated`, one reflective BSDF that is neither a blend nor a
  // coating. sigmaA: the layer's absorption coefficient; thickness in its inverse units.
  std::vector<Material> coated;
  ColorParam sigmaA{Color(0.0f)};
  float thickness = 1;

  float relativeIOR() const { return intIOR / extIOR; }
  // The non-blend BSDFs of a blend tree (1 for any other material).
  int blendLeaves() const {
    return kind == BsdfKind::Blend ? blendParts[0].blendLeaves() + blendParts[1].blendLeaves() : 1;
  }
  float roughnessV() const { return alphaV > 0 ? alphaV : alpha; }
  // surfaceAt adjusts the shading frame at its hits: a map, or a frame along dp/du.
  bool adjustsShadingFrame() const { return shadingMap != ShadingMap::None || anisotropic(); }
  // The BSDF depends on the azimuth around the normal: its shading frame must follow dp/du.
  bool isCoating() const { return kind == BsdfKind::Coating || kind == BsdfKind::RoughCoating; }
  bool anisotropic() const {
    if (kind == BsdfKind::Blend) return blendParts[0].anisotropic() || blendParts[1].anisotropic();
    if (isCoating()) return coated[0].anisotropic();
    return (kind == BsdfKind::RoughConductor || kind == BsdfKind::RoughDielectric || kind == BsdfKind::Ward) &&
           alphaV > 0 && alphaV != alpha;
  }
  // A smooth coating's own reflection is a Dirac lobe, a rough coating's is not; under either,
  // the coated BSDF's Dirac lobes stay Dirac (refracted in and out, a mirror stays a mirror).
  bool isPureSpecular() const {
    if (kind == BsdfKind::Blend) return blendParts[0].isPureSpecular() && blendParts[1].isPureSpecular();
    if (kind == BsdfKind::Coating) return coated[0].isPureSpecular();
    if (kind == BsdfKind::RoughCoating) return false;
    return kind == BsdfKind::Conductor || kind == BsdfKind::Dielectric || kind == BsdfKind::ThinDielectric;
  }
  bool hasSpecular() const {
    if (kind == BsdfKind::Blend) return blendParts[0].hasSpecular() || blendParts[1].hasSpecular();
    if (kind == BsdfKind::Coating) return true;
    if (kind == BsdfKind::RoughCoating) return coated[0].hasSpecular();
    return isPureSpecular() || kind == BsdfKind::Plastic;
  }
};

// Resolved colour parameters of a material at one surface point.
struct SurfaceColors {
  Color reflectance, specularReflectance, specularTransmittance;
  // blendbsdf: the weight of the second part and each part's own colours; coating,
  // roughcoating: parts[0] holds the coated BSDF's colours.
  float blendWeight = 0;
  Color coatAbsorption{0.0f};  // coating, roughcoating: sigma_a * thickness
  struct Part {
    Color reflectance, specularReflectance, specularTransmittance;
  } parts[kMaxBlendLeaves];
  // A blend tree: parts[0, leaves) are the colours of its non-blend BSDFs in order, the first
  // part holding firstLeaves of them; nested[] has the blends inside it in preorder (first
  // part's, then second part's), each with its weight and its own first part's leaf count.
  uint8_t leaves = 1, firstLeaves = 1;
  struct Nested {
    float weight = 0;
    uint8_t firstLeaves = 1;
  } nested[kMaxBlendLeaves - 2];
  // The colours of part i of this blend (or of a coating's coated BSDF, i = 0).
  SurfaceColors part(int i) const {
    const int first = i == 0 ? 0 : firstLeaves;
    const int count = i == 0 ? firstLeaves : leaves - firstLeaves;
    SurfaceColors c;
    c.reflectance = parts[first].reflectance;
    c.specularReflectance = parts[first].specularReflectance;
    c.specularTransmittance = parts[first].specularTransmittance;
    if (count > 1) {  // the part is a blend: its leaves, and its own node and nested blends
      const int node = i == 0 ? 0 : firstLeaves - 1;
      c.leaves = uint8_t(count);
      c.firstLeaves = nested[node].firstLeaves;
      c.blendWeight = nested[node].weight;
      for (int k = 0; k < count; ++k) c.parts[k] = parts[first + k];
      for (int k = 0; k + 2 < count; ++k) c.nested[k] = nested[node + 1 + k];
    }
    return c;
  }
};

namespace detail {

// A blendbsdf weight: its channels' mean, clamped to [0, 1].
inline float blendWeightOf(Color w) {
  const float mean = (w.x + w.y + w.z) / 3;
  return mean > 0 ? (mean < 1 ? mean : 1.0f) : 0.0f;
}

// Appends the colours of blend part p (a leaf, or a nested blend and its parts) to c.
template <class Resolve>
void resolveBlendPart(const Material& p, Resolve& resolve, SurfaceColors& c, int& leaf, int& node) {
  if (p.kind == BsdfKind::Blend) {
    if (node < kMaxBlendLeaves - 2)
      c.nested[node] = {blendWeightOf(resolve(p.blendWeight)), uint8_t(p.blendParts[0].blendLeaves())};
    ++node;
    for (const Material& q : p.blendParts) resolveBlendPart(q, resolve, c, leaf, node);
    return;
  }
  if (leaf < kMaxBlendLeaves)
    c.parts[leaf] = {resolve(p.reflectance), resolve(p.specularReflectance), resolve(p.specularTransmittance)};
  ++leaf;
}

}  // namespace detail

// The colours of `m` with each parameter resolved by resolve(const ColorParam&) -> Color (its
// constant, or its texture at a surface point).
template <class Resolve>
SurfaceColors resolveSurfaceColors(const Material& m, Resolve&& resolve) {
  SurfaceColors c;
  c.reflectance = resolve(m.reflectance);
  c.specularReflectance = resolve(m.specularReflectance);
  c.specularTransmittance = resolve(m.specularTransmittance);
  if (m.isCoating()) {
    const Material& under = m.coated[0];
    c.parts[0] = {resolve(under.reflectance), resolve(under.specularReflectance), resolve(under.specularTransmittance)};
    c.coatAbsorption = resolve(m.sigmaA) * m.thickness;
  }
  if (m.kind == BsdfKind::Blend) {
    c.blendWeight = detail::blendWeightOf(resolve(m.blendWeight));
    c.leaves = uint8_t(m.blendLeaves());
    c.firstLeaves = uint8_t(m.blendParts[0].blendLeaves());
    int leaf = 0, node = 0;
    for (const Material& p : m.blendParts) detail::resolveBlendPart(p, resolve, c, leaf, node);
  }
  return c;
}

}  // namespace erpt
