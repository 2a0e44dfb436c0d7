// Mitsuba plugin names of materials and emitters, for `erpt info` and the Python module.
#include "erpt/scene_names.h"

namespace erpt {

const char* bsdfKindName(BsdfKind k) {
  switch (k) {
    case BsdfKind::Diffuse: return "diffuse";
    case BsdfKind::Conductor: return "conductor";
    case BsdfKind::RoughConductor: return "roughconductor";
    case BsdfKind::Dielectric: return "dielectric";
    case BsdfKind::ThinDielectric: return "thindielectric";
    case BsdfKind::Plastic: return "plastic";
    case BsdfKind::Blend: return "blendbsdf";
    case BsdfKind::Ward: return "ward";
    case BsdfKind::RoughPlastic: return "roughplastic";
    case BsdfKind::RoughDielectric: return "roughdielectric";
    case BsdfKind::Phong: return "phong";
    case BsdfKind::Coating: return "coating";
    case BsdfKind::RoughCoating: return "roughcoating";
  }
  return "?";
}
const char* emitterKindName(const Emitter& e) {
  switch (e.kind) {
    case EmitterKind::Area: return "area";
    case EmitterKind::Point: return e.spot ? "spot" : "point";
    case EmitterKind::Directional: return "directional";
    case EmitterKind::Constant: return e.map ? "envmap" : "constant";
  }
  return "?";
}

}  // namespace erpt
