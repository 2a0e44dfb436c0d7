// A loaded scene in the renderer's own layout: one world-space triangle soup stored as
// structure-of-arrays columns (positions, shading normals, uvs per vertex; indices, material,
// emitter and shape per triangle), exact spheres in columns of their own, plus materials,
// textures, emitters, camera and film.
//
// Primitive ids: every hit and every surface point names one primitive of one id space,
// triangles first (0 .. triangleCount - 1), then spheres (triangleCount + sphere index), then
// the triangles of every `instance` (InstanceSet::firstPrimitive[k] + the triangle's index in
// its group), which are stored once per shapegroup and traced as Embree instances.
#pragma once

#include <cstdint>
#include <string>
#include <memory>
#include <vector>

#include "erpt/error.h"
#include "erpt/environment_map.h"
#include "erpt/material.h"
#include "erpt/math.h"

namespace erpt {

struct TriangleSoup {
  // per vertex
  std::vector<float> px, py, pz;
  std::vector<float> nx, ny, nz;  // shading normals (valid where the triangle's smooth flag is set)
  std::vector<float> u, v;        // texture coordinates (0 where the mesh has none)
  // per triangle
  std::vector<uint32_t> v0, v1, v2;
  std::vector<int32_t> material;  // index into Scene::materials
  std::vector<int32_t> emitter;   // index into Scene::emitters, -1 when not emissive
  std::vector<int32_t> shape;     // index into Scene::shapes
  std::vector<uint8_t> smooth;    // 1: interpolate vertex normals; 0: use the face normal

  size_t vertexCount() const { return px.size(); }
  size_t triangleCount() const { return v0.size(); }
  Vec3 position(uint32_t i) const { return {px[i], py[i], pz[i]}; }
  Vec3 normal(uint32_t i) const { return {nx[i], ny[i], nz[i]}; }
  // Geometric (face) normal of a triangle, unnormalized; its length is twice the area.
  Vec3 faceNormal(uint32_t tri) const {
    Vec3 a = position(v0[tri]);
    return cross(position(v1[tri]) - a, position(v2[tri]) - a);
  }
};

// Exact spheres (Mitsuba's `sphere` shape), one row each. The frame orients the sphere's own
// coordinates (texture u from the azimuth around frame.n, v from the polar angle), as the
// shape's to_world rotates them.
struct SphereSet {
  std::vector<float> cx, cy, cz, radius;
  std::vector<Frame> frame;
  std::vector<int32_t> material, emitter, shape;
  std::vector<uint8_t> flipped;  // 1: normals (and emission) point inwards

  size_t count() const { return radius.size(); }
  Vec3 center(uint32_t i) const { return {cx[i], cy[i], cz[i]}; }
  float area(uint32_t i) const { return 4 * kPi * radius[i] * radius[i]; }
};

// `shapegroup`s placed by `instance`s, traced as Embree instances (not copies): each group's
// triangles are stored once, in the group's own space, in `prototypes` (group g owns
// prototype triangles groupFirstTriangle[g] .. + groupTriangleCount[g]); each instance names
// its group and its to_world. Members that cannot be shared this way (exact spheres, emitters,
// masks, normal/bump maps, anisotropic roughness: they need world-space data per triangle) are
// copied into the world mesh instead.
struct InstanceSet {
  TriangleSoup prototypes;
  // per group
  std::vector<uint32_t> groupFirstTriangle, groupTriangleCount;
  std::vector<Vec3> groupLower, groupUpper;  // bounds of the group's vertices, group space
  // per instance
  std::vector<uint32_t> group;
  std::vector<uint32_t> firstPrimitive;  // set when the scene has loaded (scene.h's id space)
  std::vector<Transform> toWorld;
  std::vector<Transform> normalToWorld;  // the inverse transpose of toWorld (apply with vector())
  std::vector<uint8_t> mirrored;         // toWorld flips handedness: the winding's normal turns

  size_t count() const { return group.size(); }
  size_t groupCount() const { return groupFirstTriangle.size(); }
  // The instance whose primitive range holds `primitive` (one of the instanced ids).
  uint32_t instanceOf(uint32_t primitive) const;
  // The prototype triangle behind an instanced primitive of instance k.
  uint32_t prototypeTriangle(uint32_t k, uint32_t primitive) const {
    return groupFirstTriangle[group[k]] + (primitive - firstPrimitive[k]);
  }
  uint64_t instancedTriangleCount() const;
};

struct ShapeInfo {
  std::string type;  // obj, ply, rectangle, ...
  std::string id;
  SourceLocation where;
  uint32_t firstTriangle = 0, triangleCount = 0;
  int sphere = -1;  // index into Scene::spheres when the shape is an exact sphere
  int group = -1;   // a shapegroup member stored once: its triangles are InstanceSet::prototypes'
};

enum class EmitterKind { Area, Point, Constant, Directional };

struct Emitter {
  EmitterKind kind = EmitterKind::Area;
  Color radiance{0.0f};  // area and constant: radiance; point: intensity (W/sr); directional: irradiance
  Vec3 position;         // point
  int shape = -1;        // area: the shape it is attached to
  // Point lights that are Mitsuba `spot` lights: full intensity within beamWidth of the axis,
  // falling linearly in angle to 0 at cutoffAngle (radians); omnidirectional when not a spot.
  bool spot = false;
  Vec3 axis{0.0f, 0.0f, 1.0f};  // spot: where it shines; directional: where its light travels
  float cutoffAngle = kPi, beamWidth = kPi;
  // Constant emitters that are Mitsuba `envmap`s: radiance by direction (then `radiance` holds
  // the map's mean, which weighs it among the lights).
  std::shared_ptr<const EnvironmentMap> map;

  // Environment (constant or map): the radiance arriving from world direction d.
  Color environmentRadiance(Vec3 d) const { return map ? map->eval(d) : radiance; }

  // The share of the intensity sent along unit direction w (leaving the light): 1 for an
  // omnidirectional point light.
  float falloff(Vec3 w) const {
    if (!spot) return 1.0f;
    const float cosTheta = dot(w, axis);
    if (cosTheta >= std::cos(beamWidth)) return 1.0f;
    if (cosTheta <= std::cos(cutoffAngle)) return 0.0f;
    return (cutoffAngle - std::acos(cosTheta)) / (cutoffAngle - beamWidth);
  }
};

enum class FilterKind { Box, Tent, Gaussian };
// How the path tracer's samples reach the film (docs/film-splatting.md): Fis (filter importance
// sampling), Splat (normalised by the weights), SplatUnbiased (by their expectation), or Auto
// (per filter).
enum class FilmMode { Auto, Fis, Splat, SplatUnbiased };

enum class FovAxis { X, Y, Diagonal, Smaller, Larger };

struct CameraSettings {
  Transform toWorld;
  float fovDegrees = 39.3077f;  // measured along fovAxis; converted once the film size is known
  FovAxis fovAxis = FovAxis::X;
  float nearClip = 1e-2f, farClip = 1e4f;
  // `thinlens`: a lens disk of this radius (0: a pinhole) focused at focusDistance.
  float apertureRadius = 0, focusDistance = 0;
};

struct FilmSettings {
  int width = 768, height = 576;
  FilterKind filter = FilterKind::Gaussian;  // Mitsuba's default reconstruction filter
};

struct IntegratorSettings {
  std::string type = "path";
  int maxDepth = -1;  // Mitsuba's meaning: -1 unbounded, 1 = directly visible emitters only
  int spp = 4;
};

struct Scene {
  std::string file;
  TriangleSoup mesh;
  SphereSet spheres;
  InstanceSet instances;
  std::vector<ShapeInfo> shapes;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<Emitter> emitters;
  CameraSettings camera;
  FilmSettings film;
  IntegratorSettings integrator;
  Warnings warnings;
  size_t droppedDegenerateTriangles = 0;

  // Whether a ray may stop on triangle `triangle` at barycentrics (b1, b2): false only in the
  // cut-out part of a `mask` material (opacity below 0.5). Emitters are never cut (light
  // sampling picks points by area).
  bool opaqueAt(uint32_t triangle, float b1, float b2) const;
  bool hasMasks() const;
  // Some material perturbs shading normals (normalmap / bumpmap) or needs its shading frame
  // along dp/du (anisotropic roughness); set when the scene loads, read by surfaceAt so scenes
  // without either pay nothing.
  bool adjustsShadingFrames = false;

  // Resolves the (possibly textured) colours of a material at texture coordinates (u, v).
  SurfaceColors surfaceColors(int material, float u, float v) const;
  const Emitter* environment() const;

  // The primitive id space (see the top of this file).
  size_t worldPrimitiveCount() const { return mesh.triangleCount() + spheres.count(); }  // own world-space data
  size_t primitiveCount() const { return worldPrimitiveCount() + size_t(instances.instancedTriangleCount()); }
  bool isSphere(uint32_t primitive) const {
    return primitive >= mesh.triangleCount() && primitive < worldPrimitiveCount();
  }
  bool isInstanced(uint32_t primitive) const { return primitive >= worldPrimitiveCount(); }
  uint32_t sphereOf(uint32_t primitive) const { return primitive - uint32_t(mesh.triangleCount()); }
  uint32_t spherePrimitive(uint32_t sphere) const { return uint32_t(mesh.triangleCount()) + sphere; }
  // Instanced triangles never emit (emitting members are copied into the world mesh).
  int emitterOf(uint32_t primitive) const {
    if (primitive < mesh.triangleCount()) return mesh.emitter[primitive];
    return isSphere(primitive) ? spheres.emitter[sphereOf(primitive)] : -1;
  }
  // Surface area of a primitive.
  float primitiveArea(uint32_t primitive) const;
};

}  // namespace erpt
