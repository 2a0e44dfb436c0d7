// Emission sampling for light tracing: BDPT's light subpaths start here. The light is chosen
// as next-event estimation chooses it (by power); then a point uniformly by area (triangles,
// spheres) and a cosine-distributed direction on its emitting side, a direction uniform over
// the sphere or a spot's cone (point lights), or, for infinite lights, the direction light
// arrives from (the environment's own importance sampling; the directional light's fixed
// one) and a point on a disk across the scene facing it.
#include <cmath>

#include "core/warp.h"
#include "models/light_sampler.h"

namespace erpt {

namespace {
// A spot's cone, sampled uniformly up to its cutoff angle (its falloff is in the value).
float spotConePdf(const Emitter& e) { return 1.0f / (2 * kPi * (1 - std::cos(e.cutoffAngle))); }
}  // namespace

Vec3 LightSampler::beamOrigin(Vec3 direction, float u1, float u2) const {
  float x, y;
  squareToDisk(u1, u2, x, y);
  const Frame frame(direction);
  return sceneCenter_ + (frame.s * x + frame.t * y - direction) * sceneRadius_;
}

float LightSampler::beamDensity() const { return 1.0f / (kPi * sceneRadius_ * sceneRadius_); }

bool LightSampler::sampleEmission(double uPick, float u1, float u2, float u3, float u4, EmissionSample& out) const {
  if (cdf_.empty()) return false;
  float prob;
  const Item& item = pick(uPick, prob);
  out = EmissionSample{};
  if (item.kind == Kind::Triangle || item.kind == Kind::Sphere) {
    Vec3 p, n;
    if (item.kind == Kind::Triangle) {
      const TriangleSoup& m = scene_.mesh;
      float b1, b2;
      squareToTriangle(u1, u2, b1, b2);
      p = m.position(m.v0[item.index]) * (1 - b1 - b2) + m.position(m.v1[item.index]) * b1 +
          m.position(m.v2[item.index]) * b2;
      n = normalize(m.faceNormal(item.index));
    } else {
      const SphereSet& s = scene_.spheres;
      const uint32_t i = scene_.sphereOf(item.index);
      const Vec3 radial = squareToUniformSphere(u1, u2);
      p = s.center(i) + radial * s.radius[i];
      n = s.flipped[i] ? -radial : radial;
    }
    out.emitter = scene_.emitterOf(item.index);
    if (!sampleEmissionDirection(out.emitter, n, u3, u4, out.direction, out.pdfDirection)) return false;
    out.origin = p;
    out.normal = n;
    out.primitive = item.index;
    out.value = scene_.emitters[size_t(out.emitter)].radiance;
    out.pdfPosition = prob / item.area;
    out.cosAtLight = dot(n, out.direction);
    return out.pdfPosition > 0;
  }
  const Emitter& e = scene_.emitters[item.index];
  out.emitter = int(item.index);
  if (item.kind == Kind::Point) {
    out.origin = e.position;
    out.deltaPosition = true;
    sampleEmissionDirection(out.emitter, Vec3(0.0f), u3, u4, out.direction, out.pdfDirection);
    out.value = e.radiance * e.falloff(out.direction);
    out.pdfPosition = prob;
    return !isBlack(out.value);
  }
  out.infinite = true;
  out.pdfDirection = beamDensity();
  if (item.kind == Kind::Directional) {
    out.direction = e.axis;
    out.deltaDirection = true;
    out.value = e.radiance;
    out.pdfPosition = prob;
  } else {  // the environment: the direction light arrives from, as next-event estimation samples it
    Vec3 toward;
    float pdf = kUniformSpherePdf;
    if (e.map) {
      if (!e.map->sample(u3, u4, toward, pdf, &out.value)) return false;
    } else {
      toward = squareToUniformSphere(u3, u4);
      out.value = e.radiance;
    }
    out.direction = -toward;
    out.pdfPosition = prob * pdf;
  }
  out.normal = out.direction;
  out.origin = beamOrigin(out.direction, u1, u2);
  return out.pdfPosition > 0 && !isBlack(out.value);
}

bool LightSampler::sampleEmissionDirection(int emitter, Vec3 normal, float u3, float u4, Vec3& direction,
                                           float& pdf) const {
  pdf = 0;
  const Emitter& e = scene_.emitters[size_t(emitter)];
  if (e.kind == EmitterKind::Area) {
    const Vec3 local = squareToCosineHemisphere(u3, u4);
    if (!(local.z > 0)) return false;
    direction = Frame(normal).toWorld(local);
    pdf = local.z * kInvPi;
    return true;
  }
  if (e.kind != EmitterKind::Point) return false;
  if (e.spot) {
    const float cosCut = std::cos(e.cutoffAngle);
    const float cosTheta = 1 - u3 * (1 - cosCut), sinTheta = std::sqrt(std::max(0.0f, 1 - cosTheta * cosTheta));
    const float phi = 2 * kPi * u4;
    direction = Frame(e.axis).toWorld({sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta});
    pdf = spotConePdf(e);
  } else {
    direction = squareToUniformSphere(u3, u4);
    pdf = kUniformSpherePdf;
  }
  return true;
}

float LightSampler::emissionDirectionDensity(int emitter, Vec3 normal, Vec3 direction) const {
  const Emitter& e = scene_.emitters[size_t(emitter)];
  if (e.kind == EmitterKind::Area) return std::max(0.0f, dot(normal, direction)) * kInvPi;
  if (e.kind != EmitterKind::Point) return 0.0f;
  if (!e.spot) return kUniformSpherePdf;
  return dot(direction, e.axis) >= std::cos(e.cutoffAngle) ? spotConePdf(e) : 0.0f;
}

float LightSampler::emissionPositionDensity(int emitter) const {
  if (emitter < 0 || size_t(emitter) >= scene_.emitters.size()) return 0.0f;
  switch (scene_.emitters[size_t(emitter)].kind) {
    case EmitterKind::Area: {
      // Every primitive of a uniformly bright emitter has the same pick probability per area.
      const int64_t primitive = emitterPrimitive_[size_t(emitter)];
      return primitive < 0 ? 0.0f : pickProbability(uint32_t(primitive)) / scene_.primitiveArea(uint32_t(primitive));
    }
    case EmitterKind::Point: return emitterProbability_[size_t(emitter)];
    default: return 0.0f;
  }
}

void LightSampler::emissionDensity(int emitter, uint32_t primitive, Vec3 normal, Vec3 direction, float& pdfPosition,
                                   float& pdfDirection) const {
  pdfPosition = pdfDirection = 0;
  if (emitter < 0) return;
  const Emitter& e = scene_.emitters[size_t(emitter)];
  switch (e.kind) {
    case EmitterKind::Area: {
      const float prob = pickProbability(primitive);
      if (prob == 0) return;
      pdfPosition = prob / scene_.primitiveArea(primitive);
      pdfDirection = emissionDirectionDensity(emitter, normal, direction);
      return;
    }
    case EmitterKind::Point:
      pdfPosition = emitterProbability_[size_t(emitter)];
      pdfDirection = emissionDirectionDensity(emitter, normal, direction);
      return;
    case EmitterKind::Directional:
      pdfPosition = emitterProbability_[size_t(emitter)];
      pdfDirection = beamDensity();
      return;
    case EmitterKind::Constant:
      pdfPosition = pdfEnvironment(-direction);
      pdfDirection = beamDensity();
      return;
  }
}

}  // namespace erpt
