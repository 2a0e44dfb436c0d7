// Chooses emitters by power and points on them uniformly by area (ERPT's path-density
// rule 4 assumes uniform-by-area light sampling). An emissive triangle's power is
// pi * area * lum(radiance), so within one uniformly bright area light the choice is
// uniform by area; point lights weigh 4 pi lum(intensity); the constant environment weighs
// 4 pi^2 R^2 lum(radiance) for the scene's bounding radius R (pbrt's estimate).
#pragma once

#include <vector>

#include "erpt/scene.h"

namespace erpt {

struct LightSample {
  Vec3 position;     // on the emitter (for the environment: far along `direction`)
  Vec3 normal;       // emitter surface normal (area lights)
  Vec3 direction;    // unit vector from the reference point towards the light
  float distance;    // to the light point (infinite lights: +inf)
  Color radiance;    // radiance arriving along -direction (point light: intensity / d^2)
  float pdf;         // solid angle pdf at the reference point (0 for a point light: a Dirac)
  float pdfLight;    // in the light's own measure: area lights p_light * p_area (area measure),
                     // point lights the pick probability, the environment its solid-angle pdf
  bool delta;        // point light: cannot be hit by BSDF sampling
  bool environment;
  int emitter = -1;  // index into Scene::emitters
};

class LightSampler {
 public:
  explicit LightSampler(const Scene& scene);
  bool empty() const { return cdf_.empty(); }
  // Samples a light as seen from `ref`; false if the sample carries nothing.
  bool sample(Vec3 ref, float uPick, float u1, float u2, LightSample& out) const;
  // Solid-angle pdf that sample() picks point `p` (normal `n`) on emissive triangle `tri`
  // from `ref`.
  float pdfTriangle(uint32_t tri, Vec3 ref, Vec3 p, Vec3 n) const;
  float pdfEnvironment() const;
  // Area-measure density of next-event estimation picking a point on triangle `tri`
  // (p_light * p_area); for a point light, the probability of picking it.
  float pdfAreaTriangle(uint32_t tri) const;
  float pickProbabilityOfEmitter(int emitter) const;
  // Radiance an area light emits from triangle `tri` towards direction `w` (one-sided).
  Color emitted(uint32_t tri, Vec3 w) const;
  const Scene& scene() const { return scene_; }

 private:
  enum class Kind { Triangle, Point, Environment };
  struct Item {
    Kind kind;
    uint32_t index;  // triangle index or emitter index
    float area;
  };
  const Scene& scene_;
  std::vector<Item> items_;
  std::vector<float> cdf_;  // normalized, cdf_.back() == 1
  std::vector<float> triangleProbability_;  // per scene triangle (0 if not emissive)
  std::vector<float> emitterProbability_;   // per point / environment emitter
  float environmentProbability_ = 0;
  float sceneRadius_ = 1;
  Vec3 sceneCenter_;
};

}  // namespace erpt
