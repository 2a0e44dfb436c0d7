// Chooses emitters by power, then a point on the chosen one. Triangles: uniformly by area.
// Spheres seen from outside: uniformly in the cone of directions the sphere subtends (the
// visible cap only, never the hidden half), otherwise (a reference point inside, or a sphere
// that emits inwards) uniformly by area. An emissive primitive's power is
// pi * area * lum(radiance), so within one uniformly bright area light the choice is
// uniform by area; point lights weigh 4 pi lum(intensity); the constant environment weighs
// 4 pi^2 R^2 lum(radiance) for the scene's bounding radius R (pbrt's estimate), a directional
// light pi R^2 lum(irradiance).
// ERPT never samples lights after the seed pass (its mutations keep the light vertex or trace
// towards it), so the choice of technique here only changes the seeds' variance.
#pragma once

#include <vector>

#include "core/soa.h"
#include "models/surface.h"

// A light item as the vector shading kernels sample it, one row per item: a triangle as
// sampleTriangle reads it, a sphere as sampleSphere does, the environment as sample() does
// (its map is LightSampler::sampledEnvironment()'s; kind 0: an item they leave to sample()).
#define ERPT_PACKET_LIGHT_FIELDS(F, V, C)                                                           \
  F(int32_t, kind, 0, "PacketLightKind")                                                            \
  V(a, "triangle: corner 0; sphere: centre")                                                        \
  V(b, "triangle: corner 1")                                                                        \
  V(c, "triangle: corner 2")                                                                        \
  V(normal, "triangle: unit face normal")                                                           \
  F(float, radius, 0, "sphere: radius")                                                             \
  F(float, flipped, 0, "sphere: 1 when it emits inwards (sampled by area)")                         \
  C(radiance, "emitted radiance (an environment without a map: its constant radiance)")             \
  F(float, probability, 0, "p_light, the item's pick probability")                                  \
  F(float, pdfArea, 0, "area density of sampling a point of it by area, p_light / area")            \
  F(int32_t, emitter, -1, "index into Scene::emitters (-1: not a packet light)")

namespace erpt {

enum PacketLightKind : int32_t {
  kNoPacketLight = 0,
  kTrianglePacketLight = 1,
  kSpherePacketLight = 2,
  kEnvironmentPacketLight = 3
};

ERPT_SOA_STRUCT(PacketLightQueue, ERPT_PACKET_LIGHT_FIELDS)

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
  uint32_t primitive = 0;  // area lights: the primitive the point lies on
};

// A light point and a direction it sends light in, for light tracing (BDPT's light subpaths;
// light_emission.cpp). Infinite lights (environment, directional) start their rays on a disk
// of the scene's bounding radius facing the direction, outside the scene.
struct EmissionSample {
  Vec3 origin;     // the light point, or the point on the disk (infinite lights)
  Vec3 normal;     // area lights: the emitting side's normal; infinite lights: the direction
  Vec3 direction;  // unit: where the light travels
  Color value;     // radiance (area, environment), intensity with the spot falloff (point),
                   // irradiance (directional), sent along `direction`
  float pdfPosition = 0;   // density of the light vertex, pick probability included: per unit
                           // area (area lights), the pick probability (point, directional: a
                           // Dirac), the direction's solid-angle pdf (environment)
  float pdfDirection = 0;  // density of the first hit: per solid angle from the point (area,
                           // point), per unit area across the beam (infinite lights)
  float cosAtLight = 1;    // |cos| to the area light's normal (1 for the others)
  bool infinite = false, deltaPosition = false, deltaDirection = false;
  int emitter = -1;
  uint32_t primitive = 0;  // area lights
};

class LightSampler {
 public:
  explicit LightSampler(const Scene& scene);
  bool empty() const { return cdf_.empty(); }
  // Samples a light as seen from `ref`; false if the sample carries nothing.
  bool sample(Vec3 ref, double uPick, float u1, float u2, LightSample& out) const;
  // Solid-angle pdf at `ref` that sample() picks the surface point `light` (a ray from ref
  // hit it).
  float pdfSolidAngle(const SurfacePoint& light, Vec3 ref) const;
  // Solid-angle pdf that sample() picks the environment along world direction `direction`.
  float pdfEnvironment(Vec3 direction) const;
  // env.environmentRadiance(direction) and pdfEnvironment(direction) together, with one lookup
  // of the map when env is the environment this sampler picks (the same bits as the two calls).
  Color environmentRadianceAndPdf(const Emitter& env, Vec3 direction, float& pdf) const;
  // Area-measure density at point p (normal n) of `primitive` of sample() from `ref`
  // (p_light * p_area).
  float pdfArea(uint32_t primitive, Vec3 ref, Vec3 p, Vec3 n) const;
  float pickProbabilityOfEmitter(int emitter) const;
  // pdfArea for a point of area emitter `emitter` (a triangle mesh or a sphere), which every
  // primitive of a uniformly bright emitter shares; 0 for an emitter sample() never picks.
  float pdfAreaOfEmitter(int emitter, Vec3 ref, Vec3 p, Vec3 n) const;
  // Radiance an area light emits from surface point `sp` towards direction `w` (one-sided:
  // along the geometric normal's side).
  Color emitted(const SurfacePoint& sp, Vec3 w) const;
  const Scene& scene() const { return scene_; }

  // sample()'s light choice when it falls on a triangle, a sphere or the environment, for
  // kernels that finish the sample themselves (shade_path_diffuse.cpp): the light's row in
  // packetLights(). False when uPick picks any other kind of light.
  bool pickPacketLight(double uPick, uint32_t& row) const;
  // One row per light item (kind 0 for items that are neither triangles nor spheres), so that
  // kernels can gather a packet's lights in vector lanes.
  const PacketLightQueue& packetLights() const { return packetLights_; }
  // Whether pickPacketLight can ever succeed (some light is a triangle, a sphere or the
  // environment), so that kernels on scenes lit only otherwise need not try it for every hit.
  bool hasPacketLights() const { return hasPacketLights_; }
  // The environment emitter sample() can pick (nullptr: none).
  const Emitter* sampledEnvironment() const { return environment_; }

  // Emission sampling (light_emission.cpp): a light by power (the same choice as sample()),
  // a point on it and a direction, with their densities. False when it carries nothing.
  bool sampleEmission(double uPick, float u1, float u2, float u3, float u4, EmissionSample& out) const;
  // sampleEmission's densities (pdfPosition, pdfDirection) of emitting from a light vertex in
  // `direction` (unit, where the light travels): an area light's point of `primitive` with
  // emitting normal `normal`, or the point, directional or environment light `emitter`.
  void emissionDensity(int emitter, uint32_t primitive, Vec3 normal, Vec3 direction, float& pdfPosition,
                       float& pdfDirection) const;
  // The direction part of sampleEmission for an area light's point with emitting normal
  // `normal` (cosine-distributed) or point light `emitter` (its sphere or spot cone), with its
  // solid-angle pdf; false for infinite lights or a degenerate sample.
  bool sampleEmissionDirection(int emitter, Vec3 normal, float u3, float u4, Vec3& direction, float& pdf) const;
  // sampleEmission's density of the light vertex of area or point emitter `emitter` (per unit
  // area, the pick probability included; a point light's pick probability); 0 for the others.
  float emissionPositionDensity(int emitter) const;
  // sampleEmissionDirection's solid-angle density of `direction` from an area light's point
  // with emitting normal `normal` or from point light `emitter`; 0 for the others.
  float emissionDirectionDensity(int emitter, Vec3 normal, Vec3 direction) const;
  // Radius of the disk infinite lights emit from (the scene's bounding radius).
  float sceneRadius() const { return sceneRadius_; }

 private:
  enum class Kind { Triangle, Sphere, Point, Environment, Directional };
  struct Item {
    Kind kind;
    uint32_t index;  // primitive id (triangles, spheres) or emitter index
    float area;
    // A triangle's corners and unit face normal, copied here so that sampling it reads one
    // item instead of following the mesh's index and vertex arrays (and renormalizing).
    Vec3 a{}, b{}, c{}, normal{};
  };
  // 1 - cos of the half-angle of the cone sphere `sphere` subtends at `ref`, when sample()
  // samples that cone from there; 0 when it samples the sphere by area instead.
  float sphereCone(uint32_t sphere, Vec3 ref) const;
  // An infinite light's ray along `direction`: from a point of the disk of the scene's radius
  // that faces it, outside the scene; the density per unit area across the beam.
  Vec3 beamOrigin(Vec3 direction, float u1, float u2) const;
  float beamDensity() const;
  // The item sample() and sampleEmission() take for uPick, and its probability.
  const Item& pick(double uPick, float& probability) const;
  size_t pickIndex(double uPick) const;  // pick's item; cdf_ must not be empty
  float itemProbability(size_t i) const { return cdf_[i] - (i > 0 ? cdf_[i - 1] : 0.0f); }
  // The probability of picking a primitive's light (0 for one that does not emit).
  float pickProbability(uint32_t primitive) const;
  bool sampleTriangle(const Item& item, float prob, Vec3 ref, float u1, float u2, LightSample& out) const;
  bool sampleSphere(const Item& item, float prob, Vec3 ref, float u1, float u2, LightSample& out) const;
  // Finishes an area-measure sample at point p, normal n of `primitive`.
  bool finishAreaSample(uint32_t primitive, float pdfArea, Vec3 ref, Vec3 p, Vec3 n, LightSample& out) const;
  const Scene& scene_;
  std::vector<Item> items_;
  std::vector<float> cdf_;  // normalized, cdf_.back() == 1
  PacketLightQueue packetLights_;  // row i: items_[i] as the vector kernels sample it
  std::vector<float> primitiveProbability_;  // per world primitive id (0 if not emissive; instanced ids are past it)
  std::vector<float> emitterProbability_;   // per point / environment emitter
  std::vector<int64_t> emitterPrimitive_;   // per emitter: one of its light-sampled primitives, -1 none
  bool hasPacketLights_ = false;
  float environmentProbability_ = 0;
  const Emitter* environment_ = nullptr;  // the environment emitter, when it can be picked
  float sceneRadius_ = 1;
  Vec3 sceneCenter_;
};

}  // namespace erpt
