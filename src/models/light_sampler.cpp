#include "erpt/light_sampler.h"

#include <algorithm>

#include "erpt/warp.h"

namespace erpt {

LightSampler::LightSampler(const Scene& scene) : scene_(scene) {
  const TriangleSoup& mesh = scene.mesh;
  Vec3 lo(1e30f), hi(-1e30f);
  for (size_t i = 0; i < mesh.vertexCount(); ++i)
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], mesh.position(uint32_t(i))[a]);
      hi[a] = std::max(hi[a], mesh.position(uint32_t(i))[a]);
    }
  if (mesh.vertexCount() > 0) {
    sceneCenter_ = (lo + hi) * 0.5f;
    sceneRadius_ = std::max(1e-3f, 0.5f * length(hi - lo));
  }
  std::vector<double> weights;
  for (uint32_t t = 0; t < mesh.triangleCount(); ++t) {
    if (mesh.emitter[t] < 0) continue;
    float area = 0.5f * length(mesh.faceNormal(t));
    double w = double(area) * kPi * luminance(scene.emitters[mesh.emitter[t]].radiance);
    if (w <= 0) continue;
    items_.push_back({Kind::Triangle, t, area});
    weights.push_back(w);
  }
  for (uint32_t e = 0; e < scene.emitters.size(); ++e) {
    const Emitter& em = scene.emitters[e];
    double lum = luminance(em.radiance);
    if (lum <= 0) continue;
    if (em.kind == EmitterKind::Point) {
      items_.push_back({Kind::Point, e, 0});
      weights.push_back(4 * kPi * lum);
    } else if (em.kind == EmitterKind::Constant) {
      items_.push_back({Kind::Environment, e, 0});
      weights.push_back(4.0 * kPi * kPi * double(sceneRadius_) * sceneRadius_ * lum);
    }
  }
  double total = 0;
  for (double w : weights) total += w;
  double running = 0;
  triangleProbability_.assign(mesh.triangleCount(), 0.0f);
  emitterProbability_.assign(scene.emitters.size(), 0.0f);
  for (size_t i = 0; i < items_.size(); ++i) {
    running += weights[i];
    cdf_.push_back(float(running / total));
    float p = float(weights[i] / total);
    if (items_[i].kind == Kind::Triangle) triangleProbability_[items_[i].index] = p;
    if (items_[i].kind == Kind::Environment) environmentProbability_ = p;
    if (items_[i].kind != Kind::Triangle) emitterProbability_[items_[i].index] = p;
  }
  if (!cdf_.empty()) cdf_.back() = 1.0f;
}

Color LightSampler::emitted(uint32_t tri, Vec3 w) const {
  int e = scene_.mesh.emitter[tri];
  if (e < 0 || dot(scene_.mesh.faceNormal(tri), w) <= 0) return Color(0.0f);
  return scene_.emitters[e].radiance;
}

float LightSampler::pdfTriangle(uint32_t tri, Vec3 ref, Vec3 p, Vec3 n) const {
  float prob = triangleProbability_[tri];
  if (prob == 0) return 0.0f;
  float area = 0.5f * length(scene_.mesh.faceNormal(tri));
  Vec3 d = p - ref;
  float dist2 = dot(d, d);
  float cosL = std::abs(dot(n, d)) / std::sqrt(dist2);
  if (cosL <= 0) return 0.0f;
  return prob / area * dist2 / cosL;  // area measure -> solid angle
}

float LightSampler::pdfAreaTriangle(uint32_t tri) const {
  float prob = triangleProbability_[tri];
  return prob > 0 ? prob / (0.5f * length(scene_.mesh.faceNormal(tri))) : 0.0f;
}

float LightSampler::pickProbabilityOfEmitter(int emitter) const { return emitterProbability_[emitter]; }

float LightSampler::pdfEnvironment() const { return environmentProbability_ * kUniformSpherePdf; }

bool LightSampler::sample(Vec3 ref, float uPick, float u1, float u2, LightSample& out) const {
  if (cdf_.empty()) return false;
  size_t i = std::min(size_t(std::upper_bound(cdf_.begin(), cdf_.end(), uPick) - cdf_.begin()), cdf_.size() - 1);
  const Item& item = items_[i];
  float prob = cdf_[i] - (i > 0 ? cdf_[i - 1] : 0.0f);
  out = LightSample{};
  if (item.kind == Kind::Triangle) {
    const TriangleSoup& m = scene_.mesh;
    float b1, b2;
    squareToTriangle(u1, u2, b1, b2);
    Vec3 a = m.position(m.v0[item.index]), b = m.position(m.v1[item.index]), c = m.position(m.v2[item.index]);
    out.position = a * (1 - b1 - b2) + b * b1 + c * b2;
    out.normal = normalize(m.faceNormal(item.index));
    Vec3 d = out.position - ref;
    float dist2 = dot(d, d);
    out.distance = std::sqrt(dist2);
    out.direction = d / out.distance;
    float cosL = -dot(out.normal, out.direction);
    if (cosL <= 0 || dist2 == 0) return false;  // one-sided emission: we see its back
    out.emitter = m.emitter[item.index];
    out.radiance = scene_.emitters[out.emitter].radiance;
    out.pdfLight = prob / item.area;
    out.pdf = out.pdfLight * dist2 / cosL;
  } else if (item.kind == Kind::Point) {
    const Emitter& e = scene_.emitters[item.index];
    out.emitter = int(item.index);
    Vec3 d = e.position - ref;
    float dist2 = dot(d, d);
    if (dist2 == 0) return false;
    out.position = e.position;
    out.distance = std::sqrt(dist2);
    out.direction = d / out.distance;
    out.radiance = e.radiance / (dist2 * prob);  // the pick probability folded in
    out.pdf = 0;
    out.pdfLight = prob;
    out.delta = true;
  } else {
    out.direction = squareToUniformSphere(u1, u2);
    out.distance = std::numeric_limits<float>::infinity();
    out.position = sceneCenter_ + out.direction * (4 * sceneRadius_);
    out.emitter = int(item.index);
    out.radiance = scene_.emitters[item.index].radiance;
    out.pdf = prob * kUniformSpherePdf;
    out.pdfLight = out.pdf;
    out.environment = true;
  }
  return true;
}

}  // namespace erpt
