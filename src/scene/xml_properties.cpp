#include "xml_properties.h"

#include <algorithm>
#include <cctype>

#include "models/spectrum.h"

namespace erpt::xml {

void Properties::set(const std::string& name, Property p) { props_[name] = std::move(p); }

const Property* Properties::find(const std::string& name) const {
  auto it = props_.find(name);
  if (it == props_.end()) return nullptr;
  it->second.used = true;
  return &it->second;
}

const Property* Properties::findTag(const std::string& tag) const {
  for (auto& [name, p] : props_)
    if (p.tag == tag) {
      p.used = true;
      return &p;
    }
  return nullptr;
}

const Property& Properties::require(const std::string& name, const char* tag) const {
  const Property* p = find(name);
  if (!p) throw InputError(where_, std::string("missing parameter '") + name + "' of " + plugin_);
  if (tag && p->tag != tag && !(std::string(tag) == "float" && p->tag == "integer"))
    throw InputError(p->where, "parameter '" + name + "' of " + plugin_ + " should be <" + tag + ">, not <" + p->tag + ">");
  return *p;
}

float Properties::getFloat(const std::string& name, float fallback) const {
  if (!has(name)) return fallback;
  const Property& p = require(name, nullptr);
  return float(parseNumber(p.value, p.where, "'" + name + "'"));
}

int Properties::getInt(const std::string& name, int fallback) const {
  if (!has(name)) return fallback;
  const Property& p = require(name, nullptr);
  return parseInteger(p.value, p.where, "'" + name + "'");
}

bool Properties::getBool(const std::string& name, bool fallback) const {
  if (!has(name)) return fallback;
  const Property& p = require(name, nullptr);
  return parseBoolean(p.value, p.where, "'" + name + "'");
}

std::string Properties::getString(const std::string& name, const std::string& fallback) const {
  if (!has(name)) return fallback;
  return require(name, nullptr).value;
}

Vec3 Properties::getPoint(const std::string& name, Vec3 fallback) const {
  if (!has(name)) return fallback;
  const Property& p = require(name, nullptr);
  return parseVector(p.value, p.where, "'" + name + "'");
}

Color Properties::getColor(const std::string& name, Color fallback) const {
  if (!has(name)) return fallback;
  const Property& p = require(name, nullptr);
  if (p.tag == "texture") throw InputError(p.where, "parameter '" + name + "' of " + plugin_ + " cannot be a texture");
  return parseColorValue(p);
}

ColorParam Properties::getColorParam(const std::string& name, Color fallback, const Scene& scene) const {
  if (!has(name)) return {fallback, -1};
  const Property& p = require(name, nullptr);
  if (p.tag != "texture") return {parseColorValue(p), -1};
  // The constant part holds the texture's mean: used where one colour must stand for it.
  const Texture& t = scene.textures[p.texture];
  Color mean = (t.color0 + t.color1) * 0.5f;
  if (t.kind == TextureKind::Bitmap) {
    mean = Color(0.0f);
    for (const Color& c : t.texels) mean += c;
    mean = mean / float(std::max<size_t>(1, t.texels.size()));
  }
  return {mean, p.texture};
}

Transform Properties::getTransform(const std::string& name) const {
  if (!has(name)) return Transform{};
  return require(name, "transform").transform;
}

float Properties::getIOR(const std::string& name, float fallback) const {
  if (!has(name)) return fallback;
  const Property& p = require(name, nullptr);
  float ior;
  if (p.tag == "string") {
    std::string key = p.value;
    for (char& c : key) c = char(std::tolower((unsigned char)c));
    if (!namedIOR(key, ior)) throw InputError(p.where, "unknown index of refraction '" + p.value + "'");
  } else {
    ior = float(parseNumber(p.value, p.where, "'" + name + "'"));
  }
  if (!(ior > 0)) throw InputError(p.where, "index of refraction '" + name + "' must be positive");
  return ior;
}

void Properties::warnUnused(Warnings& warnings) const {
  for (const auto& [name, p] : props_)
    if (!p.used) warnings.add(p.where, "parameter '" + name + "' of " + plugin_ + " is not supported; ignored");
}

void Properties::rename(const std::string& alias, const std::string& canonical) {
  auto it = props_.find(alias);
  if (it == props_.end()) return;
  auto other = props_.find(canonical);
  if (other != props_.end())
    throw InputError(it->second.where, "'" + alias + "' and '" + canonical + "' (line " +
                                           std::to_string(other->second.where.line) + ") of " + plugin_ +
                                           " name the same parameter; give only one");
  Property p = std::move(it->second);
  props_.erase(it);
  props_.emplace(canonical, std::move(p));
}

namespace {

// Parameters a plugin takes under two names, by element and plugin type; names as
// normalizeName gives them, so each entry serves both dialects. Mitsuba 0.6's BSDFs, emitters
// and textures have no other aliases (difftrans's `diffuseTransmittance` belongs to a plugin
// erpt does not read).
struct ParameterAlias {
  const char* element;
  const char* type;
  const char* alias;
  const char* canonical;
};
constexpr ParameterAlias kParameterAliases[] = {
    {"bsdf", "diffuse", "diffuse_reflectance", "reflectance"},
    {"bsdf", "roughdiffuse", "diffuse_reflectance", "reflectance"},
};

}  // namespace

bool hasParameterAliases(const std::string& element) {
  for (const ParameterAlias& a : kParameterAliases)
    if (element == a.element) return true;
  return false;
}

void resolveAliases(const std::string& element, const std::string& type, Properties& props) {
  for (const ParameterAlias& a : kParameterAliases)
    if (element == a.element && type == a.type) props.rename(a.alias, a.canonical);
}

Color srgbToLinear(Color c) {
  Color out;
  for (int i = 0; i < 3; ++i) {
    float v = c[i];
    out[i] = v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
  }
  return out;
}

Color spectrumToRgb(const std::vector<std::pair<double, double>>& s) {
  // Linear between the samples, zero outside them; a single sample is a flat spectrum.
  auto value = [&](double w) {
    if (s.size() == 1) return s[0].second;
    if (w < s.front().first || w > s.back().first) return 0.0;
    size_t i = 1;
    while (i + 1 < s.size() && s[i].first < w) ++i;
    double t = (w - s[i - 1].first) / std::max(1e-9, s[i].first - s[i - 1].first);
    return s[i - 1].second * (1 - t) + s[i].second * t;
  };
  // Normalizing by the equal-energy spectrum's RGB makes flat spectra exactly grey.
  static const Color white = spectrumToLinearRgb([](double) { return 1.0; });
  return spectrumToLinearRgb(value) / white;
}

Color parseColorValue(const Property& p) {
  const std::string what = "colour value";
  if (p.tag == "srgb") {
    std::string v = p.value;
    if (!v.empty() && v[0] == '#') {
      if (v.size() != 7) throw InputError(p.where, "bad sRGB colour '" + v + "' (expected #rrggbb)");
      Color c;
      for (int i = 0; i < 3; ++i) {
        char* end = nullptr;
        std::string byte = v.substr(1 + 2 * i, 2);
        long b = std::strtol(byte.c_str(), &end, 16);
        if (*end != '\0') throw InputError(p.where, "bad sRGB colour '" + v + "'");
        c[i] = float(b) / 255.0f;
      }
      return srgbToLinear(c);
    }
    return srgbToLinear(parseVector(v, p.where, what));
  }
  if (p.tag == "spectrum" && p.value.find(':') != std::string::npos) {
    std::vector<std::pair<double, double>> samples;
    std::string item;
    auto flush = [&] {
      size_t colon = item.find(':');
      if (item.find_first_not_of(" \t\n") == std::string::npos) return;
      if (colon == std::string::npos) throw InputError(p.where, "bad spectrum entry '" + item + "' (expected nm:value)");
      samples.emplace_back(parseNumber(item.substr(0, colon), p.where, "wavelength"),
                           parseNumber(item.substr(colon + 1), p.where, "spectrum value"));
    };
    for (char c : p.value) {
      if (c == ',') {
        flush();
        item.clear();
      } else {
        item += c;
      }
    }
    flush();
    for (size_t i = 1; i < samples.size(); ++i)
      if (samples[i].first <= samples[i - 1].first)
        throw InputError(p.where, "spectrum wavelengths must increase");
    if (samples.empty()) throw InputError(p.where, "empty spectrum");
    return spectrumToRgb(samples);
  }
  if (p.tag == "rgb" || p.tag == "spectrum" || p.tag == "float" || p.tag == "integer" || p.tag == "blackbody")
    return parseVector(p.value, p.where, what);
  throw InputError(p.where, "expected a colour (<rgb>, <srgb>, <spectrum>), got <" + p.tag + ">");
}

bool namedIOR(const std::string& name, float& ior) {
  static const std::map<std::string, float> table = {
      {"vacuum", 1.0f},         {"helium", 1.000036f},     {"hydrogen", 1.000132f},     {"air", 1.000277f},
      {"carbon dioxide", 1.00045f}, {"water", 1.3330f},    {"acetone", 1.36f},          {"ethanol", 1.361f},
      {"carbon tetrachloride", 1.461f}, {"glycerol", 1.4729f}, {"benzene", 1.501f},     {"silicone oil", 1.52045f},
      {"bromine", 1.661f},      {"water ice", 1.31f},      {"fused quartz", 1.458f},    {"pyrex", 1.470f},
      {"acrylic glass", 1.49f}, {"polypropylene", 1.49f},  {"bk7", 1.5046f},            {"sodium chloride", 1.544f},
      {"amber", 1.55f},         {"pet", 1.5750f},          {"diamond", 2.419f}};
  auto it = table.find(name);
  if (it == table.end()) return false;
  ior = it->second;
  return true;
}

// RGB fits of measured spectral data (values near 650/550/450 nm); approximate.
bool namedConductor(const std::string& name, Color& eta, Color& k) {
  struct Entry { Color eta, k; };
  static const std::map<std::string, Entry> table = {
      {"none", {{0, 0, 0}, {1, 1, 1}}},
      {"au", {{0.1431f, 0.3749f, 1.4425f}, {3.9831f, 2.3857f, 1.6032f}}},
      {"ag", {{0.1552f, 0.1167f, 0.1383f}, {4.8283f, 3.1222f, 2.1469f}}},
      {"cu", {{0.2004f, 0.9240f, 1.1022f}, {3.9129f, 2.4528f, 2.1421f}}},
      {"al", {{1.6574f, 0.8803f, 0.5212f}, {9.2238f, 6.2695f, 4.8370f}}},
      {"cr", {{4.3696f, 2.9167f, 1.6547f}, {5.2064f, 4.2313f, 3.7549f}}},
      {"w", {{4.3707f, 3.3002f, 2.9982f}, {3.5006f, 2.6004f, 2.2695f}}},
      {"hg", {{2.3989f, 1.4400f, 0.9095f}, {6.0365f, 4.5301f, 3.4066f}}}};
  std::string key = name;
  for (char& c : key) c = char(std::tolower((unsigned char)c));
  auto it = table.find(key);
  if (it == table.end()) return false;
  eta = it->second.eta;
  k = it->second.k;
  return true;
}

}  // namespace erpt::xml
