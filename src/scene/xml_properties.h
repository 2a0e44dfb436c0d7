// Internal to the scene loader: the parameters of one plugin element (<float name=...>,
// <rgb>, <transform>, nested textures...), looked up by normalized name.
#pragma once

#include <map>
#include <string>

#include "erpt/scene.h"
#include "xml_document.h"

namespace erpt::xml {

struct Property {
  std::string tag;    // float, integer, boolean, string, rgb, srgb, spectrum, blackbody, point, vector, transform, texture
  // (a blackbody's value is its linear RGB, computed when read)
  std::string value;  // after $-substitution
  SourceLocation where;
  Transform transform;  // tag == "transform"
  int texture = -1;     // tag == "texture": index into Scene::textures
  mutable bool used = false;
};

class Properties {
 public:
  Properties(std::string plugin, SourceLocation where) : plugin_(std::move(plugin)), where_(std::move(where)) {}
  const std::string& plugin() const { return plugin_; }
  const SourceLocation& where() const { return where_; }
  void set(const std::string& name, Property p);
  bool has(const std::string& name) const { return props_.count(name) != 0; }
  const Property* find(const std::string& name) const;
  // The first (by name) parameter with this tag, marked used; null if none.
  const Property* findTag(const std::string& tag) const;

  float getFloat(const std::string& name, float fallback) const;
  int getInt(const std::string& name, int fallback) const;
  bool getBool(const std::string& name, bool fallback) const;
  std::string getString(const std::string& name, const std::string& fallback) const;
  Vec3 getPoint(const std::string& name, Vec3 fallback) const;
  Color getColor(const std::string& name, Color fallback) const;
  ColorParam getColorParam(const std::string& name, Color fallback, const Scene& scene) const;
  Transform getTransform(const std::string& name) const;
  // Index of refraction given as a number or a material name ("bk7", "water", ...).
  float getIOR(const std::string& name, float fallback) const;

  // One warning per parameter the plugin never read: a typo or an unsupported option.
  void warnUnused(Warnings& warnings) const;
  // Gives parameter `alias` the name `canonical`, the one the loader reads. Both given: an
  // InputError at the alias (one parameter under two names).
  void rename(const std::string& alias, const std::string& canonical);

 private:
  const Property& require(const std::string& name, const char* tag) const;
  std::string plugin_;
  SourceLocation where_;
  std::map<std::string, Property> props_;
};

// Renames the parameters that `<element type="type">` takes under another name as well (Mitsuba
// 0.6's aliases, such as a diffuse BSDF's `diffuseReflectance` for `reflectance`) to the name
// the loader reads. The aliases are declared in one table, in xml_properties.cpp.
void resolveAliases(const std::string& element, const std::string& type, Properties& props);
bool hasParameterAliases(const std::string& element);  // any plugin of this element (bsdf, ...)

// Colour conversions for <rgb>, <srgb>, <spectrum> values.
Color parseColorValue(const Property& p);
Color srgbToLinear(Color c);
// RGB of a sampled spectrum given as (wavelength nm, value) pairs; flat spectra give grey.
Color spectrumToRgb(const std::vector<std::pair<double, double>>& samples);
// Named indices of refraction and conductors (Mitsuba's names); false if unknown.
bool namedIOR(const std::string& name, float& ior);
bool namedConductor(const std::string& name, Color& eta, Color& k);

}  // namespace erpt::xml
