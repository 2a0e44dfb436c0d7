#include "kernels/bdpt_vertex.h"

namespace erpt {

VertexBsdf vertexBsdf(const Scene& scene, const BdptVertex& v) {
  if (v.material < 0 || isLightVertex(v) || v.kind == kEyeVertex) return VertexBsdf{};
  // Built from prvalues, so the colours (some 400 bytes with a blend's parts) are written once
  // where the caller wants them; assigning them to a member was a copy per vertex.
  const Material& m = scene.materials[size_t(v.material)];
  return VertexBsdf{&m, m.anisotropic() ? Frame::turned(v.ns, v.tangentAngle) : Frame(v.ns),
                    scene.surfaceColors(v.material, v.u, v.v)};
}

Color lightVertexEmission(const Scene& scene, const BdptVertex& v, Vec3 w) {
  if (v.emitter < 0) return Color(0.0f);
  const Emitter& e = scene.emitters[size_t(v.emitter)];
  switch (e.kind) {
    case EmitterKind::Area: return dot(v.ng, w) > 0 ? e.radiance : Color(0.0f);
    case EmitterKind::Point: return e.radiance * e.falloff(w);
    case EmitterKind::Directional: return e.radiance;
    case EmitterKind::Constant: return e.environmentRadiance(-w);
  }
  return Color(0.0f);
}

float nextEventDensity(const LightSampler& lights, const BdptVertex& v, Vec3 ref) {
  if (v.emitter < 0) return 0.0f;
  switch (lights.scene().emitters[size_t(v.emitter)].kind) {
    case EmitterKind::Area: return lights.pdfArea(v.primitive, ref, v.p, v.ng);
    case EmitterKind::Constant: return lights.pdfEnvironment(v.ng);
    default: return lights.pickProbabilityOfEmitter(v.emitter);
  }
}

BdptVertex lightVertexOf(const Scene& scene, const LightSample& ls) {
  BdptVertex v;
  v.emitter = ls.emitter;
  const EmitterKind kind = scene.emitters[size_t(ls.emitter)].kind;
  v.primitive = ls.primitive;
  v.p = ls.position;
  if (ls.environment || kind == EmitterKind::Directional) {
    v.kind = kEnvironmentVertex;
    v.ng = ls.direction;
  } else {
    v.kind = kLightVertex;
    v.ng = kind == EmitterKind::Area ? ls.normal : Vec3(0.0f);
  }
  v.ns = v.ng;
  return v;
}

}  // namespace erpt
