#include "models/light_sampler.h"

#include <algorithm>

#include "core/cdf_search.h"
#include "core/warp.h"

namespace erpt {

LightSampler::LightSampler(const Scene& scene) : scene_(scene) {
  const TriangleSoup& mesh = scene.mesh;
  const SphereSet& spheres = scene.spheres;
  Vec3 lo(1e30f), hi(-1e30f);
  auto grow = [&](Vec3 p, float r) {
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], p[a] - r);
      hi[a] = std::max(hi[a], p[a] + r);
    }
  };
  for (size_t i = 0; i < mesh.vertexCount(); ++i) grow(mesh.position(uint32_t(i)), 0.0f);
  for (uint32_t i = 0; i < spheres.count(); ++i) grow(spheres.center(i), spheres.radius[i]);
  const InstanceSet& instances = scene.instances;
  for (size_t k = 0; k < instances.count(); ++k) {  // the corners of each group's box, placed
    const Vec3 lower = instances.groupLower[instances.group[k]], upper = instances.groupUpper[instances.group[k]];
    for (int corner = 0; corner < 8; ++corner)
      grow(instances.toWorld[k].point({corner & 1 ? upper.x : lower.x, corner & 2 ? upper.y : lower.y,
                                       corner & 4 ? upper.z : lower.z}),
           0.0f);
  }
  if (mesh.vertexCount() + spheres.count() + instances.count() > 0) {
    sceneCenter_ = (lo + hi) * 0.5f;
    sceneRadius_ = std::max(1e-3f, 0.5f * length(hi - lo));
  }
  std::vector<double> weights;
  for (uint32_t p = 0; p < scene.worldPrimitiveCount(); ++p) {  // instanced triangles never emit
    const int e = scene.emitterOf(p);
    if (e < 0) continue;
    float area = scene.primitiveArea(p);
    double w = double(area) * kPi * luminance(scene.emitters[e].radiance);
    if (w <= 0) continue;
    Item item{scene.isSphere(p) ? Kind::Sphere : Kind::Triangle, p, area};
    if (item.kind == Kind::Triangle) {
      item.a = mesh.position(mesh.v0[p]), item.b = mesh.position(mesh.v1[p]), item.c = mesh.position(mesh.v2[p]);
      item.normal = normalize(mesh.faceNormal(p));
    }
    hasPacketLights_ = true;
    items_.push_back(item);
    weights.push_back(w);
  }
  for (uint32_t e = 0; e < scene.emitters.size(); ++e) {
    const Emitter& em = scene.emitters[e];
    double lum = luminance(em.radiance);
    if (lum <= 0) continue;
    if (em.kind == EmitterKind::Point) {
      items_.push_back({Kind::Point, e, 0});
      // A spot's power: the solid angle of its cone, counting the falloff band as half.
      const double cone = em.spot ? 2 * kPi * (1 - 0.5 * (std::cos(em.beamWidth) + std::cos(em.cutoffAngle))) : 4 * kPi;
      weights.push_back(cone * lum);
    } else if (em.kind == EmitterKind::Directional) {
      items_.push_back({Kind::Directional, e, 0});
      weights.push_back(kPi * double(sceneRadius_) * sceneRadius_ * lum);  // through the scene's disk
    } else if (em.kind == EmitterKind::Constant) {
      items_.push_back({Kind::Environment, e, 0});
      weights.push_back(4.0 * kPi * kPi * double(sceneRadius_) * sceneRadius_ * lum);
    }
  }
  double total = 0;
  for (double w : weights) total += w;
  double running = 0;
  primitiveProbability_.assign(scene.worldPrimitiveCount(), 0.0f);
  emitterProbability_.assign(scene.emitters.size(), 0.0f);
  emitterPrimitive_.assign(scene.emitters.size(), -1);
  for (size_t i = 0; i < items_.size(); ++i) {
    running += weights[i];
    cdf_.push_back(float(running / total));
    float p = float(weights[i] / total);
    const Kind kind = items_[i].kind;
    if (kind == Kind::Triangle || kind == Kind::Sphere) {
      primitiveProbability_[items_[i].index] = p;
      int64_t& first = emitterPrimitive_[size_t(scene.emitterOf(items_[i].index))];
      if (first < 0) first = items_[i].index;
    } else emitterProbability_[items_[i].index] = p;
    if (kind == Kind::Environment) {
      environmentProbability_ = p;
      environment_ = &scene.emitters[items_[i].index];
    }
  }
  if (!cdf_.empty()) cdf_.back() = 1.0f;
  packetLights_.resize(items_.size());
  for (size_t i = 0; i < items_.size(); ++i) {
    PacketLightQueue::Row row;  // kind 0 and emitter -1 unless a triangle or a sphere
    const Item& item = items_[i];
    if (item.kind == Kind::Triangle) {
      row.kind = kTrianglePacketLight;
      row.a = item.a, row.b = item.b, row.c = item.c, row.normal = item.normal;
      row.emitter = scene.emitterOf(item.index);
    } else if (item.kind == Kind::Sphere) {
      const uint32_t sphere = scene.sphereOf(item.index);
      row.kind = kSpherePacketLight;
      row.a = scene.spheres.center(sphere);
      row.radius = scene.spheres.radius[sphere];
      row.flipped = scene.spheres.flipped[sphere] ? 1.0f : 0.0f;
      row.emitter = scene.spheres.emitter[sphere];
    } else if (item.kind == Kind::Environment && environment_ == &scene.emitters[item.index]) {
      row.kind = kEnvironmentPacketLight;
      row.emitter = int32_t(item.index);
      row.probability = itemProbability(i);
      row.radiance = environment_->radiance;
      hasPacketLights_ = true;
      packetLights_.setRow(i, row);
      continue;
    } else {
      packetLights_.setRow(i, row);
      continue;
    }
    row.probability = itemProbability(i);
    row.pdfArea = itemProbability(i) / item.area;  // as sampleTriangle and sampleSphere compute it
    row.radiance = scene.emitters[size_t(row.emitter)].radiance;
    packetLights_.setRow(i, row);
  }
}

Color LightSampler::emitted(const SurfacePoint& sp, Vec3 w) const {
  if (sp.emitter < 0 || dot(sp.geometricNormal, w) <= 0) return Color(0.0f);
  return scene_.emitters[sp.emitter].radiance;
}

float LightSampler::sphereCone(uint32_t sphere, Vec3 ref) const {
  const SphereSet& s = scene_.spheres;
  if (s.flipped[sphere]) return 0.0f;  // lit from inside: the visible part is no cone
  const Vec3 d = s.center(sphere) - ref;
  const float dist2 = dot(d, d), r2 = s.radius[sphere] * s.radius[sphere];
  // Points on or just inside the surface (a ray origin pushed off it) sample by area.
  if (!(dist2 > r2 * 1.0001f)) return 0.0f;
  const float sin2Max = r2 / dist2;
  const float cosMax = std::sqrt(std::max(0.0f, 1 - sin2Max));
  return sin2Max / (1 + cosMax);  // = 1 - cosMax without the cancellation for small cones
}

float LightSampler::pickProbability(uint32_t primitive) const {
  return primitive < primitiveProbability_.size() ? primitiveProbability_[primitive] : 0.0f;
}

float LightSampler::pdfSolidAngle(const SurfacePoint& light, Vec3 ref) const {
  const float prob = pickProbability(light.primitive);
  if (prob == 0) return 0.0f;
  if (scene_.isSphere(light.primitive)) {
    const float cone = sphereCone(scene_.sphereOf(light.primitive), ref);
    if (cone > 0) return prob / (2 * kPi * cone);
  }
  const Vec3 d = light.position - ref;
  const float dist2 = dot(d, d);
  const float cosL = std::abs(dot(light.geometricNormal, d)) / std::sqrt(dist2);
  if (!(cosL > 0)) return 0.0f;
  return prob / scene_.primitiveArea(light.primitive) * dist2 / cosL;  // area measure -> solid angle
}

float LightSampler::pdfArea(uint32_t primitive, Vec3 ref, Vec3 p, Vec3 n) const {
  const float prob = pickProbability(primitive);
  if (prob == 0) return 0.0f;
  if (scene_.isSphere(primitive)) {
    const float cone = sphereCone(scene_.sphereOf(primitive), ref);
    if (cone > 0) {
      const Vec3 d = p - ref;
      const float dist2 = dot(d, d);
      return prob / (2 * kPi * cone) * std::abs(dot(n, d)) / (dist2 * std::sqrt(dist2));
    }
  }
  return prob / scene_.primitiveArea(primitive);
}

float LightSampler::pickProbabilityOfEmitter(int emitter) const { return emitterProbability_[emitter]; }

float LightSampler::pdfAreaOfEmitter(int emitter, Vec3 ref, Vec3 p, Vec3 n) const {
  if (emitter < 0 || size_t(emitter) >= emitterPrimitive_.size() || emitterPrimitive_[size_t(emitter)] < 0) return 0.0f;
  // A primitive's pick probability is its share of the power, pi area lum(radiance): per unit
  // area the same for every primitive of one emitter.
  return pdfArea(uint32_t(emitterPrimitive_[size_t(emitter)]), ref, p, n);
}

float LightSampler::pdfEnvironment(Vec3 direction) const {
  if (environmentProbability_ == 0) return 0.0f;
  return environmentProbability_ * (environment_->map ? environment_->map->pdf(direction) : kUniformSpherePdf);
}

Color LightSampler::environmentRadianceAndPdf(const Emitter& env, Vec3 direction, float& pdf) const {
  if (environmentProbability_ == 0 || environment_ != &env || !env.map) {
    pdf = pdfEnvironment(direction);
    return env.environmentRadiance(direction);
  }
  float mapPdf;
  const Color radiance = env.map->evalAndPdf(direction, mapPdf);
  pdf = environmentProbability_ * mapPdf;
  return radiance;
}

bool LightSampler::finishAreaSample(uint32_t primitive, float pdfArea, Vec3 ref, Vec3 p, Vec3 n,
                                    LightSample& out) const {
  out.position = p;
  out.normal = n;
  Vec3 d = p - ref;
  float dist2 = dot(d, d);
  if (!(dist2 > 0)) return false;
  out.distance = std::sqrt(dist2);
  out.direction = d / out.distance;
  float cosL = -dot(n, out.direction);
  if (cosL <= 0) return false;  // one-sided emission: we see its back
  out.emitter = scene_.emitterOf(primitive);
  out.primitive = primitive;
  out.radiance = scene_.emitters[out.emitter].radiance;
  out.pdfLight = pdfArea;
  out.pdf = pdfArea * dist2 / cosL;
  return true;
}

bool LightSampler::sampleTriangle(const Item& item, float prob, Vec3 ref, float u1, float u2, LightSample& out) const {
  float b1, b2;
  squareToTriangle(u1, u2, b1, b2);
  return finishAreaSample(item.index, prob / item.area, ref, item.a * (1 - b1 - b2) + item.b * b1 + item.c * b2,
                          item.normal, out);
}

bool LightSampler::sampleSphere(const Item& item, float prob, Vec3 ref, float u1, float u2, LightSample& out) const {
  const SphereSet& s = scene_.spheres;
  const uint32_t i = scene_.sphereOf(item.index);
  const Vec3 c = s.center(i);
  const float r = s.radius[i];
  const float cone = sphereCone(i, ref);
  if (cone == 0) {
    const Vec3 radial = squareToUniformSphere(u1, u2);
    return finishAreaSample(item.index, prob / item.area, ref, c + radial * r, s.flipped[i] ? -radial : radial, out);
  }
  // Uniform in the cone around the direction to the centre; the ray's first hit on the
  // sphere is the light point, and the direction is the one to that point. With x = 1 -
  // cos(theta) = u1 cone, the hit lies at t = dc (cos(theta) - sqrt(sin^2(thetaMax) -
  // sin^2(theta))), and sin^2(thetaMax) - sin^2(theta) = cone (2 - cone) - x (2 - x) =
  // cone (1 - u1) (2 - cone - x): a product without the cancellation near the silhouette
  // that made a float solve of the ray put the point visibly off it.
  const Vec3 toCenter = c - ref;
  const float dc = length(toCenter);
  const float oneMinusCos = u1 * cone;
  const float cosTheta = 1 - oneMinusCos;
  const float sin2Theta = oneMinusCos * (2 - oneMinusCos);
  const float sinTheta = std::sqrt(std::max(0.0f, sin2Theta)), phi = 2 * kPi * u2;
  const Frame frame(toCenter / dc);
  const Vec3 w = frame.toWorld({sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta});
  const float beyond = cone * (1 - u1) * (2 - cone - oneMinusCos);  // sin^2(thetaMax) - sin^2(theta)
  const float t = dc * (cosTheta - std::sqrt(std::max(0.0f, beyond)));
  const Vec3 radial = normalize(ref + w * t - c);
  const Vec3 p = c + radial * r;
  const Vec3 d = p - ref;
  const float dist2 = dot(d, d);
  out.position = p;
  out.normal = radial;
  out.distance = std::sqrt(dist2);
  out.direction = d / out.distance;
  const float cosL = -dot(radial, out.direction);
  if (!(cosL > 0) || !(dist2 > 0)) return false;  // grazing the silhouette
  out.emitter = s.emitter[i];
  out.primitive = item.index;
  out.radiance = scene_.emitters[out.emitter].radiance;
  out.pdf = prob / (2 * kPi * cone);
  out.pdfLight = out.pdf * cosL / dist2;
  return true;
}

size_t LightSampler::pickIndex(double uPick) const {
  return std::min(upperBoundIndex(cdf_.data(), cdf_.size(), uPick), cdf_.size() - 1);
}

const LightSampler::Item& LightSampler::pick(double uPick, float& probability) const {
  const size_t i = pickIndex(uPick);
  probability = itemProbability(i);
  return items_[i];
}

bool LightSampler::pickPacketLight(double uPick, uint32_t& row) const {
  if (cdf_.empty()) return false;
  row = uint32_t(pickIndex(uPick));
  return packetLights_.kind[row] != kNoPacketLight;
}

bool LightSampler::sample(Vec3 ref, double uPick, float u1, float u2, LightSample& out) const {
  if (cdf_.empty()) return false;
  float prob;
  const Item& item = pick(uPick, prob);
  out = LightSample{};
  if (item.kind == Kind::Triangle) return sampleTriangle(item, prob, ref, u1, u2, out);
  if (item.kind == Kind::Sphere) return sampleSphere(item, prob, ref, u1, u2, out);
  if (item.kind == Kind::Directional) {
    // A Dirac in direction: the light point stands beyond the scene's bounding sphere.
    const Emitter& e = scene_.emitters[item.index];
    out.emitter = int(item.index);
    out.direction = -e.axis;
    out.distance = 2 * (length(ref - sceneCenter_) + sceneRadius_);
    out.position = ref + out.direction * out.distance;
    out.normal = e.axis;
    out.radiance = e.radiance / prob;
    out.pdf = 0;
    out.pdfLight = prob;
    out.delta = true;
    return true;
  }
  if (item.kind == Kind::Point) {
    const Emitter& e = scene_.emitters[item.index];
    out.emitter = int(item.index);
    Vec3 d = e.position - ref;
    float dist2 = dot(d, d);
    if (dist2 == 0) return false;
    out.position = e.position;
    out.distance = std::sqrt(dist2);
    out.direction = d / out.distance;
    out.radiance = e.radiance * (e.falloff(-out.direction) / (dist2 * prob));  // the pick probability folded in
    if (isBlack(out.radiance)) return false;  // outside a spot's cone
    out.pdf = 0;
    out.pdfLight = prob;
    out.delta = true;
    return true;
  }
  // The environment: uniform directions, or the map's importance sampling.
  const Emitter& env = scene_.emitters[item.index];
  float pdfDirection = kUniformSpherePdf;
  if (env.map) {
    if (!env.map->sample(u1, u2, out.direction, pdfDirection, &out.radiance)) return false;
  } else {
    out.direction = squareToUniformSphere(u1, u2);
    out.radiance = env.radiance;
  }
  out.distance = std::numeric_limits<float>::infinity();
  out.position = sceneCenter_ + out.direction * (4 * sceneRadius_);
  out.emitter = int(item.index);
  out.pdf = prob * pdfDirection;
  out.pdfLight = out.pdf;
  out.environment = true;
  return true;
}

}  // namespace erpt
