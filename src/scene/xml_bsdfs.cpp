// <bsdf> and <texture> plugins.
#include <cmath>
#include <cstdlib>
#include <optional>
#include <sstream>

#include "models/bsdf.h"
#include "erpt/image_io.h"
#include "referenced_file.h"
#include "scene_builder.h"

namespace erpt::xml {

namespace {

MicrofacetKind readDistribution(const Properties& props, Warnings& warnings) {
  std::string d = props.getString("distribution", "beckmann");
  if (d == "ggx") return MicrofacetKind::GGX;
  if (d != "beckmann") warnings.add(props.find("distribution")->where, "distribution '" + d + "' is not supported; using beckmann");
  return MicrofacetKind::Beckmann;
}

// The roughness of `m` from alpha, or alpha_u and alpha_v (anisotropic: roughconductor and
// roughdielectric, as in Mitsuba; roughplastic and roughcoating are isotropic there: they get
// their mean).
void readAlpha(const Properties& props, Warnings& warnings, Material& m) {
  auto checked = [&](const char* name, float a) {
    if (!(a > 0 && a <= 4)) throw InputError(props.find(name) ? props.find(name)->where : props.where(),
                                             std::string(name) + " must be in (0, 4]");
    return std::max(a, 1e-4f);
  };
  m.alpha = checked("alpha", props.getFloat("alpha", 0.1f));
  m.alphaV = -1;
  if (!props.has("alpha_u") && !props.has("alpha_v")) return;
  const float au = checked("alpha_u", props.getFloat("alpha_u", m.alpha));
  const float av = checked("alpha_v", props.getFloat("alpha_v", m.alpha));
  if (m.kind == BsdfKind::RoughPlastic || m.kind == BsdfKind::RoughCoating) {
    const char* type = m.kind == BsdfKind::RoughPlastic ? "roughplastic" : "roughcoating";
    warnings.add(props.where(), std::string(type) + " is isotropic; using alpha = (alpha_u + alpha_v) / 2");
    m.alpha = 0.5f * (au + av);
    return;
  }
  m.alpha = au;
  m.alphaV = av;
}

// twosided around a blend: its parts do the shading, those of nested blends too.
void makeTwoSided(Material& m) {
  m.twoSided = true;
  for (Material& part : m.blendParts) makeTwoSided(part);
}

bool refractsSmoothly(const Material& m) { return m.kind == BsdfKind::Dielectric || m.kind == BsdfKind::ThinDielectric; }

// ERPT follows a specular chain through "the" refraction of a vertex: a blend tree keeps its
// first smooth dielectric, and every later one becomes a copy of it (taking its weight).
// Returns how many were replaced.
int keepFirstSmoothRefraction(Material& m, std::optional<Material>& first) {
  if (m.kind == BsdfKind::Blend) {
    int replaced = 0;
    for (Material& part : m.blendParts) replaced += keepFirstSmoothRefraction(part, first);
    return replaced;
  }
  if (!refractsSmoothly(m)) return 0;
  if (!first) {
    first = m;
    return 0;
  }
  m = *first;
  return 1;
}

// Mitsuba 0.6's mixturebsdf weights: numbers separated by spaces, commas or semicolons; each
// finite and not negative.
std::vector<double> mixtureWeights(const std::string& text, const SourceLocation& where) {
  std::vector<double> weights;
  size_t at = 0;
  while (at < text.size()) {
    const size_t start = text.find_first_not_of(" ,;", at);
    if (start == std::string::npos) break;
    const size_t end = std::min(text.find_first_of(" ,;", start), text.size());
    const std::string token = text.substr(start, end - start);
    char* rest = nullptr;
    const double w = std::strtod(token.c_str(), &rest);
    if (rest == token.c_str() || *rest != '\0')
      throw InputError(where, "mixturebsdf weight '" + token + "' is not a number");
    if (!std::isfinite(w) || w < 0)
      throw InputError(where, "mixturebsdf weight '" + token + "' must be finite and not negative");
    weights.push_back(w);
    at = end;
  }
  return weights;
}

}  // namespace

int SceneBuilder::defaultMaterial() {
  if (defaultMaterial_ < 0) {
    Material m;
    m.name = "(default diffuse)";
    defaultMaterial_ = int(scene_.materials.size());
    scene_.materials.push_back(m);
  }
  return defaultMaterial_;
}

int SceneBuilder::materialById(const Document& doc, const pugi::xml_node& node, const std::string& id) {
  auto it = materialIds_.find(id);
  if (it == materialIds_.end()) throw InputError(doc.where(node), "reference to unknown BSDF id '" + id + "'");
  return it->second;
}

int SceneBuilder::bsdf(const Document& doc, const pugi::xml_node& node) {
  std::vector<pugi::xml_node> children;
  Properties props = readProperties(doc, node, &children);
  std::string type = attribute(doc, node, "type");
  std::string id = attribute(doc, node, "id", false);
  // A child naming a BSDF: by value, or a <ref> that is not a texture's.
  auto isBsdf = [&](const pugi::xml_node& c) {
    const std::string tag = c.name();
    return tag == "bsdf" || (tag == "ref" && !textureIds_.count(attribute(doc, c, "id")));
  };
  auto materialOf = [&](const pugi::xml_node& c) {
    return std::string(c.name()) == "bsdf" ? bsdf(doc, c) : materialById(doc, c, attribute(doc, c, "id"));
  };
  // The first nested BSDF (index; -1: none), for wrappers.
  auto nested = [&]() -> int {
    for (const pugi::xml_node& c : children)
      if (isBsdf(c)) return materialOf(c);
    return -1;
  };
  // A wrapper (twosided, mask, normalmap, bumpmap): a copy of its nested BSDF, named after both.
  auto wrapped = [&]() -> Material {
    const int inner = nested();
    if (inner < 0) throw InputError(doc.where(node), type + " needs a nested <bsdf>");
    Material copy = scene_.materials[size_t(inner)];
    copy.name = id.empty() ? type + "(" + copy.name + ")" : id;
    return copy;
  };
  Material m;
  m.name = id.empty() ? type : id;
  Warnings& w = scene_.warnings;
  // A part of a blendbsdf or mixturebsdf (any BSDF, blends too).
  auto blendPart = [&](const pugi::xml_node& c) -> Material {
    Material part = scene_.materials[size_t(materialOf(c))];
    if (part.isCoating()) {
      w.add(doc.where(c), "a coating inside a " + type + " is not supported; using the coating's nested BSDF");
      Material under = part.coated[0];
      part = under;
    }
    // Cut-outs and shading maps act on the whole surface: only the outermost wrapper's count.
    if (part.masked || part.shadingMap != ShadingMap::None)
      w.add(doc.where(c), "a mask, normalmap or bumpmap inside a " + type + " is ignored; wrap the " + type + " instead");
    return part;
  };
  // A blend tree (nested blendbsdf and mixturebsdf): at most kMaxBlendLeaves BSDFs, and one
  // smooth dielectric.
  auto checkBlendTree = [&](Material& tree) {
    if (tree.blendLeaves() > kMaxBlendLeaves)
      throw InputError(doc.where(node), type + " holds " + std::to_string(tree.blendLeaves()) +
                                            " BSDFs with its nested blends (and any absorbed share); at most " +
                                            std::to_string(kMaxBlendLeaves) + " are supported");
    std::optional<Material> first;
    if (keepFirstSmoothRefraction(tree, first) > 0)
      w.add(doc.where(node), type + " holds more than one smooth dielectric, which is not supported; the first takes "
                                    "the weights of the others");
  };
  if (type == "diffuse" || type == "roughdiffuse") {
    m.kind = BsdfKind::Diffuse;
    m.reflectance = props.getColorParam("reflectance", Color(0.5f), scene_);
    if (type == "roughdiffuse") {
      // Oren-Nayar's roughness is not modelled: the surface keeps its reflectance, on a
      // Lambertian lobe (closer than the grey default of an unknown BSDF).
      props.find("alpha");  // Mitsuba's default is 0.2
      props.find("use_fast_approx");
      w.add(props.where(), "roughdiffuse (Oren-Nayar) is not supported; rendered as diffuse with its reflectance, "
                           "ignoring its roughness 'alpha'");
    }
  } else if (type == "twosided") {
    m = wrapped();
    makeTwoSided(m);
  } else if (type == "mask") {
    m = wrapped();
    m.masked = true;
    m.opacity = props.getColorParam("opacity", Color(0.5f), scene_);  // Mitsuba's default
    warnPartialOpacity(m.opacity, props.where());
  } else if (type == "blendbsdf") {
    m.kind = BsdfKind::Blend;
    for (const pugi::xml_node& c : children) {
      if (!isBsdf(c)) continue;
      if (m.blendParts.size() == 2) throw InputError(doc.where(c), "blendbsdf takes two nested BSDFs, not more");
      m.blendParts.push_back(blendPart(c));
    }
    if (m.blendParts.size() != 2) throw InputError(doc.where(node), "blendbsdf needs two nested BSDFs");
    // ERPT follows a specular chain through "the" refraction of a vertex: two smooth
    // dielectrics would give it two (and a wrong radiance scale for one of them).
    if (refractsSmoothly(m.blendParts[0]) && refractsSmoothly(m.blendParts[1])) {
      w.add(doc.where(node), "a blendbsdf of two smooth dielectrics is not supported; using its first BSDF");
      const std::string name = m.name;
      Material first = m.blendParts[0];
      m = first;
      m.name = name;
    } else {
      checkBlendTree(m);
    }
    m.blendWeight = props.getColorParam("weight", Color(0.5f), scene_);
    const Color wv = m.blendWeight.value;
    if (m.blendWeight.texture < 0 && !(wv.x >= 0 && wv.x <= 1 && wv.y >= 0 && wv.y <= 1 && wv.z >= 0 && wv.z <= 1))
      throw InputError(props.find("weight")->where, "blendbsdf weight must be in [0, 1]");
  } else if (type == "mixturebsdf") {
    // sum_i w_i f_i (Mitsuba 0.6), as a chain of blends: blend(A_1, blend(A_2, ...)) whose
    // weights give each A_i its share w_i; weights summing above 1 are normalized (Mitsuba's
    // ensureEnergyConservation), and below 1 the rest 1 - sum goes to a black diffuse part
    // (absorbed).
    std::vector<Material> parts;
    for (const pugi::xml_node& c : children)
      if (isBsdf(c)) parts.push_back(blendPart(c));
    if (parts.empty()) throw InputError(doc.where(node), "mixturebsdf needs nested BSDFs");
    const Property* weightsProp = props.find("weights");
    if (!weightsProp) throw InputError(doc.where(node), "mixturebsdf needs 'weights', one per nested BSDF");
    const std::vector<double> weights = mixtureWeights(props.getString("weights", ""), weightsProp->where);
    if (weights.size() != parts.size())
      throw InputError(weightsProp->where, "mixturebsdf has " + std::to_string(weights.size()) + " weights for " +
                                               std::to_string(parts.size()) + " nested BSDFs");
    double sum = 0;
    for (double x : weights) sum += x;
    if (!(sum > 0)) throw InputError(weightsProp->where, "mixturebsdf weights must not all be 0");
    const bool conserve = props.getBool("ensure_energy_conservation", true);
    if (sum > 1 && !conserve) {
      std::ostringstream total;
      total << sum;
      w.add(props.find("ensure_energy_conservation")->where,
            "mixturebsdf weights summing to " + total.str() +
                " > 1 without ensureEnergyConservation are not supported (a blend cannot add energy); normalized to 1");
    }
    const double scale = sum > 1 ? 1 / sum : 1.0;
    std::vector<Material> leaves;
    std::vector<double> shares;
    for (size_t i = 0; i < parts.size(); ++i)
      if (weights[i] > 0) {
        leaves.push_back(parts[i]);
        shares.push_back(weights[i] * scale);
      }
    if (sum < 1 - 1e-6) {
      Material black;
      black.name = m.name + " (absorbed share)";
      black.kind = BsdfKind::Diffuse;
      black.reflectance = ColorParam{Color(0.0f)};
      leaves.push_back(black);
      shares.push_back(1 - sum);
    }
    // From the back: the blend of leaves j.. takes leaf j with share p_j / (p_j + p_j+1 + ...).
    Material chain = leaves.back();
    double rest = shares.back();
    for (size_t j = leaves.size() - 1; j-- > 0;) {
      Material b;
      b.name = m.name;
      b.kind = BsdfKind::Blend;
      b.blendParts = {leaves[j], chain};
      b.blendWeight = ColorParam{Color(float(rest / (rest + shares[j])))};
      rest += shares[j];
      chain = std::move(b);
    }
    const std::string name = m.name;
    m = std::move(chain);
    m.name = name;
    checkBlendTree(m);
  } else if (type == "normalmap" || type == "bumpmap") {
    m = wrapped();
    const int map = nestedTexture(doc, props, children);
    if (map < 0) throw InputError(doc.where(node), type + " needs a <texture> (the " +
                                                       (type == "normalmap" ? "normals" : "heights") + ")");
    m.shadingMap = type == "normalmap" ? ShadingMap::Normal : ShadingMap::Bump;
    m.shadingTexture = map;
    if (type == "bumpmap") m.bumpScale = props.getFloat("scale", 1.0f);
    if (!std::isfinite(m.bumpScale)) throw InputError(props.find("scale")->where, "bumpmap scale must be finite");
  } else if (type == "conductor" || type == "roughconductor") {
    m.kind = type == "conductor" ? BsdfKind::Conductor : BsdfKind::RoughConductor;
    // Mitsuba 0.6 defaults to copper, Mitsuba 3 to a perfect mirror.
    std::string metal = props.getString("material", majorVersion_ == 0 ? "Cu" : "none");
    if (!namedConductor(metal, m.eta, m.k))
      throw InputError(props.find("material")->where, "unknown conductor material '" + metal + "'");
    m.eta = props.getColor("eta", m.eta);
    m.k = props.getColor("k", m.k);
    // The medium outside the metal (Mitsuba 0.6's `ext_eta`, air by default, a number or a
    // name): the Fresnel terms depend on eta and k relative to it. Mitsuba 3 has no exterior
    // index (1); a scene that gives one is followed.
    const float outside = props.getIOR("ext_eta", majorVersion_ == 0 ? 1.000277f : 1.0f);
    m.eta = m.eta / outside;
    m.k = m.k / outside;
    m.specularReflectance = props.getColorParam("specular_reflectance", Color(1.0f), scene_);
    if (m.kind == BsdfKind::RoughConductor) {
      readAlpha(props, w, m);
      m.distribution = readDistribution(props, w);
    }
  } else if (type == "dielectric" || type == "thindielectric" || type == "roughdielectric") {
    m.kind = type == "thindielectric" ? BsdfKind::ThinDielectric
             : type == "roughdielectric" ? BsdfKind::RoughDielectric
                                         : BsdfKind::Dielectric;
    if (m.kind == BsdfKind::RoughDielectric) {
      readAlpha(props, w, m);
      m.distribution = readDistribution(props, w);
    }
    m.intIOR = props.getIOR("int_ior", 1.5046f);
    m.extIOR = props.getIOR("ext_ior", 1.000277f);
    m.specularReflectance = props.getColorParam("specular_reflectance", Color(1.0f), scene_);
    m.specularTransmittance = props.getColorParam("specular_transmittance", Color(1.0f), scene_);
  } else if (type == "plastic" || type == "roughplastic") {
    m.kind = type == "plastic" ? BsdfKind::Plastic : BsdfKind::RoughPlastic;
    m.intIOR = props.getIOR("int_ior", 1.49f);  // polypropylene, Mitsuba's default
    m.extIOR = props.getIOR("ext_ior", 1.000277f);
    m.reflectance = props.getColorParam("diffuse_reflectance", Color(0.5f), scene_);
    m.specularReflectance = props.getColorParam("specular_reflectance", Color(1.0f), scene_);
    m.nonlinear = props.getBool("nonlinear", false);
    if (m.kind == BsdfKind::RoughPlastic) {
      readAlpha(props, w, m);
      m.distribution = readDistribution(props, w);
    }
  } else if (type == "coating" || type == "roughcoating") {
    const int inner = nested();
    if (inner < 0) throw InputError(doc.where(node), type + " needs a nested <bsdf>");
    const Material& under = scene_.materials[size_t(inner)];
    const bool transmits = under.kind == BsdfKind::Dielectric || under.kind == BsdfKind::ThinDielectric ||
                           under.kind == BsdfKind::RoughDielectric;
    std::string unsupported;
    if (transmits) unsupported = "a coating over a transmissive BSDF";
    else if (under.kind == BsdfKind::Blend) unsupported = "a coating over a blendbsdf";
    else if (under.isCoating()) unsupported = "a coating over a coating";
    else if (under.masked || under.shadingMap != ShadingMap::None) unsupported = "a coating over a mask, normalmap or bumpmap";
    if (!unsupported.empty()) {
      w.add(doc.where(node), unsupported + " is not supported; using the nested BSDF alone (no layer)");
      if (!id.empty()) materialIds_[id] = inner;
      return inner;
    }
    m.kind = type == "coating" ? BsdfKind::Coating : BsdfKind::RoughCoating;
    m.coated = {under};
    m.intIOR = props.getIOR("int_ior", 1.5046f);  // bk7, Mitsuba's default
    m.extIOR = props.getIOR("ext_ior", 1.000277f);
    m.thickness = props.getFloat("thickness", 1.0f);
    if (!(m.thickness >= 0 && std::isfinite(m.thickness)))
      throw InputError(props.find("thickness")->where, type + " thickness must be finite and not negative");
    m.sigmaA = props.getColorParam("sigma_a", Color(0.0f), scene_);
    m.specularReflectance = props.getColorParam("specular_reflectance", Color(1.0f), scene_);
    if (m.kind == BsdfKind::RoughCoating) {
      readAlpha(props, w, m);
      m.distribution = readDistribution(props, w);
    }
  } else if (type == "ward") {
    m.kind = BsdfKind::Ward;
    const std::string variant = props.getString("variant", "balanced");
    if (variant == "ward") m.wardVariant = WardVariant::Ward;
    else if (variant == "ward-duer") m.wardVariant = WardVariant::WardDuer;
    else if (variant == "balanced") m.wardVariant = WardVariant::Balanced;
    else throw InputError(props.find("variant")->where, "unknown ward variant '" + variant + "' (ward, ward-duer, balanced)");
    readAlpha(props, w, m);
    m.reflectance = props.getColorParam("diffuse_reflectance", Color(0.5f), scene_);
    m.specularReflectance = props.getColorParam("specular_reflectance", Color(0.2f), scene_);
  } else if (type == "phong") {
    m.kind = BsdfKind::Phong;
    m.exponent = props.getFloat("exponent", 30.0f);
    if (!(m.exponent >= 0 && m.exponent <= 1e6f)) throw InputError(props.where(), "phong exponent must be in [0, 1e6]");
    m.reflectance = props.getColorParam("diffuse_reflectance", Color(0.5f), scene_);
    m.specularReflectance = props.getColorParam("specular_reflectance", Color(0.2f), scene_);
  } else {
    int inner = nested();
    if (inner >= 0) {
      w.add(doc.where(node), "bsdf '" + type + "' is not supported; using its nested BSDF");
      if (!id.empty()) materialIds_[id] = inner;
      return inner;
    }
    w.add(doc.where(node), "bsdf '" + type + "' is not supported; using diffuse with reflectance 0.5");
    props = Properties(props.plugin(), props.where());  // its parameters mean nothing to diffuse
  }
  // Scenes written for rough variants (or other renderers) give smooth BSDFs a roughness.
  if ((type == "dielectric" || type == "thindielectric" || type == "conductor" || type == "plastic" || type == "coating") &&
      (props.has("alpha") || props.has("alpha_u") || props.has("alpha_v"))) {
    const std::string name = props.has("alpha") ? "alpha" : props.has("alpha_u") ? "alpha_u" : "alpha_v";
    const Property* a = props.find(name);
    props.find("alpha");
    props.find("alpha_u");
    props.find("alpha_v");
    w.add(a->where, "'" + type + "' is smooth and ignores '" + name + "'; rendered as a smooth " + type +
                        (type == "thindielectric" ? "" : " (use 'rough" + type + "' for a rough one)"));
  }
  props.warnUnused(w);
  finalizeMaterial(m);
  int index = int(scene_.materials.size());
  scene_.materials.push_back(m);
  if (!id.empty()) materialIds_[id] = index;
  return index;
}

// The texture inside a normalmap, bumpmap or scale texture: Mitsuba 3 names it (`normalmap`,
// or anything), Mitsuba 0.6 nests it unnamed; by value or by <ref> (Mitsuba takes a reference
// wherever it takes a texture).
int SceneBuilder::nestedTexture(const Document& doc, const Properties& props,
                                const std::vector<pugi::xml_node>& children) {
  if (const Property* p = props.findTag("texture")) return p->texture;
  for (const pugi::xml_node& c : children) {
    const std::string tag = c.name();
    if (tag == "texture") return texture(doc, c);
    if (tag == "ref" && textureIds_.count(attribute(doc, c, "id"))) return textureIds_.at(attribute(doc, c, "id"));
  }
  return -1;
}

void SceneBuilder::warnPartialOpacity(const ColorParam& opacity, const SourceLocation& where) {
  auto partial = [](Color c) {
    const float a = (c.x + c.y + c.z) / 3;
    return a > 0.02f && a < 0.98f;
  };
  size_t partialTexels = 0, texels = 1;
  if (opacity.texture >= 0) {
    const Texture& t = scene_.textures[size_t(opacity.texture)];
    texels = std::max<size_t>(1, t.texels.size());
    for (const Color& c : t.texels) partialTexels += partial(c);
    if (t.kind == TextureKind::Checkerboard) partialTexels = partial(t.color0) || partial(t.color1) ? texels : 0;
  } else {
    partialTexels = partial(opacity.value);
  }
  if (partialTexels * 100 > texels)
    scene_.warnings.add(where, "mask opacity between 0 and 1 is rendered as a cut-out at 0.5 (Mitsuba blends partial "
                               "opacity stochastically)");
}

int SceneBuilder::texture(const Document& doc, const pugi::xml_node& node) {
  std::vector<pugi::xml_node> children;  // a `scale` texture's nested one
  Properties props = readProperties(doc, node, &children);
  std::string type = attribute(doc, node, "type");
  std::string id = attribute(doc, node, "id", false);
  Texture t;
  // uv transform: Mitsuba 3's to_uv matrix, or Mitsuba 0.6's uscale/vscale/uoffset/voffset.
  Transform uv = props.getTransform("to_uv");
  t.uScale = float(uv(0, 0)) * props.getFloat("uscale", 1.0f) * props.getFloat("uvscale", 1.0f);
  t.vScale = float(uv(1, 1)) * props.getFloat("vscale", 1.0f) * props.getFloat("uvscale", 1.0f);
  t.uOffset = float(uv(0, 3)) + props.getFloat("uoffset", 0.0f);
  t.vOffset = float(uv(1, 3)) + props.getFloat("voffset", 0.0f);
  if (type == "bitmap") {
    t.kind = TextureKind::Bitmap;
    const Property* file = props.find("filename");
    if (!file) throw InputError(doc.where(node), "bitmap texture needs a 'filename'");
    std::string path = resolvePath(doc, file->value, file->where);
    requireFile(path, file->where, "texture file");
    bool srgb = false;
    RgbImage img = readReferencedFile(file->where, [&] { return readImage(path, &srgb); });
    bool raw = props.getBool("raw", false);
    for (Color& c : img.pixels) c = (srgb && !raw) ? srgbToLinear(c) : c;
    t.width = img.width;
    t.height = img.height;
    t.texels = std::move(img.pixels);
    for (const char* ignored : {"filter_type", "wrap_mode", "gamma"}) props.find(ignored);
  } else if (type == "scale") {
    // A texture times a constant (Mitsuba 0.6's way of scaling a bump map's heights): baked.
    // As in Mitsuba 0.6, the scaled thing may also be a constant `value`, and the scale a colour.
    int inner = nestedTexture(doc, props, children);
    if (inner < 0 && props.has("value")) {
      Texture constant;
      constant.color0 = constant.color1 = props.getColor("value", Color(1.0f));
      inner = int(scene_.textures.size());
      scene_.textures.push_back(constant);
    }
    if (inner < 0) {
      for (const pugi::xml_node& c : children)
        if (std::string(c.name()) == "ref")
          throw InputError(doc.where(c), "reference to unknown texture id '" + attribute(doc, c, "id") + "'");
      throw InputError(doc.where(node), "scale texture needs a nested <texture> (or a <ref> to one)");
    }
    const Color factor = props.getColor("scale", Color(1.0f));
    if (!(std::isfinite(factor.x) && std::isfinite(factor.y) && std::isfinite(factor.z)))
      throw InputError(props.find("scale")->where, "texture scale must be finite");
    t = scene_.textures[size_t(inner)];
    for (Color& c : t.texels) c = c * factor;
    t.color0 = t.color0 * factor;
    t.color1 = t.color1 * factor;
  } else if (type == "checkerboard") {
    t.kind = TextureKind::Checkerboard;
    t.color0 = props.getColor("color0", Color(0.4f));
    t.color1 = props.getColor("color1", Color(0.2f));
  } else {
    scene_.warnings.add(doc.where(node), "texture '" + type + "' is not supported; using a grey checkerboard");
    t.color0 = t.color1 = Color(0.5f);
    props = Properties(props.plugin(), props.where());
  }
  if (type != "scale")
    for (const pugi::xml_node& c : children)
      scene_.warnings.add(doc.where(c), "<" + std::string(c.name()) + "> is not supported inside <texture>; ignored");
  props.warnUnused(scene_.warnings);
  int index = int(scene_.textures.size());
  scene_.textures.push_back(std::move(t));
  if (!id.empty()) textureIds_[id] = index;
  return index;
}

}  // namespace erpt::xml
