// BDPT's per-vertex math (docs/bdpt.md): directions and density conversions between subpath
// vertices, the BSDF at a vertex, and what a light vertex emits and how it is sampled.
//
// Vertex kinds: kEyeVertex (the camera: the pinhole or the lens point, ng the optical axis),
// kNonSpecularVertex / kSpecularVertex (a surface, by the lobe the walk took there),
// kLightVertex (an area or point light's point; a point light has ng = 0) and
// kEnvironmentVertex (a vertex at infinity: the environment, or a directional light; its ng
// is the unit direction from the scene towards it).
#pragma once

#include "core/queues.h"
#include "models/bsdf.h"
#include "models/camera.h"
#include "models/light_sampler.h"

namespace erpt {

using BdptVertex = BdptVertexQueue::Row;

inline bool atInfinity(const BdptVertex& v) { return v.kind == kEnvironmentVertex; }
inline bool isLightVertex(const BdptVertex& v) { return v.kind == kLightVertex || v.kind == kEnvironmentVertex; }

// Unit direction from a towards b.
inline Vec3 directionTo(const BdptVertex& a, const BdptVertex& b) {
  if (atInfinity(b)) return b.ng;
  if (atInfinity(a)) return -a.ng;
  return normalize(b.p - a.p);
}

// A solid-angle density at `from` of the direction towards `to`, as a density of `to`: per unit
// area (solid angle when `to` is at infinity; from an infinite light the density is per unit
// area across its beam, so only the cosine at `to` converts it).
inline float areaDensity(float pdf, const BdptVertex& from, const BdptVertex& to) {
  if (atInfinity(to)) return pdf;
  if (atInfinity(from)) return pdf * std::abs(dot(to.ng, from.ng));
  const Vec3 d = to.p - from.p;
  const float d2 = dot(d, d);
  if (!(d2 > 0)) return 0.0f;
  return pdf * std::abs(dot(to.ng, d)) / (d2 * std::sqrt(d2));
}

// A surface vertex's BSDF: its material, shading frame and colours.
struct VertexBsdf {
  const Material* material = nullptr;
  Frame frame;
  SurfaceColors colors;
  // The vertex a BSDF sample or connection can leave from (not a pure Dirac material).
  bool connectable() const { return material && !material->isPureSpecular(); }
  // Solid-angle density of sampling `to` arriving from `from` (either side).
  float pdf(Vec3 from, Vec3 to) const { return bsdfPdf(*material, colors, frame.toLocal(from), frame.toLocal(to)); }
  // A connection's three numbers from directions already in the vertex's frame (each
  // direction is taken to local coordinates once, not once per number): f(towardCamera,
  // towardLight) |cos(towardLight)| (radiance transport, Dirac lobes excluded), and the
  // densities pdf(towardCamera, towardLight) and pdf(towardLight, towardCamera). Returns false
  // (and only f is set) when f is black: the connection carries nothing and needs no density.
  bool connection(Vec3 towardCameraLocal, Vec3 towardLightLocal, Color& f, float& pdfToLight,
                  float& pdfToCamera) const {
    if (material->kind == BsdfKind::Diffuse) {
      // The commonest vertex, written out (the same bits as the three calls below): both
      // directions on the side the camera's direction arrives on (either side of a two-sided
      // surface), the cosine lobe's value and densities.
      const float flip =
          towardCameraLocal.z > 0 ? 1.0f : (material->twoSided && towardCameraLocal.z < 0 ? -1.0f : 0.0f);
      const float cameraZ = towardCameraLocal.z * flip, lightZ = towardLightLocal.z * flip;
      if (!(cameraZ > 0) || !(lightZ > 0)) {
        f = Color(0.0f);
        return false;
      }
      f = colors.reflectance * (lightZ * kInvPi);
      pdfToLight = lightZ * kInvPi;
      pdfToCamera = cameraZ * kInvPi;
      return !isBlack(f);
    }
    f = bsdfEval(*material, colors, towardCameraLocal, towardLightLocal);
    if (isBlack(f)) return false;
    pdfToLight = bsdfPdf(*material, colors, towardCameraLocal, towardLightLocal);
    pdfToCamera = bsdfPdf(*material, colors, towardLightLocal, towardCameraLocal);
    return true;
  }
};
VertexBsdf vertexBsdf(const Scene& scene, const BdptVertex& v);

// Radiance (or intensity, irradiance) light vertex `v` sends along unit direction w.
Color lightVertexEmission(const Scene& scene, const BdptVertex& v, Vec3 w);
// The density with which next-event estimation from `ref` picks light vertex `v`
// (LightSample::pdfLight's measure).
float nextEventDensity(const LightSampler& lights, const BdptVertex& v, Vec3 ref);
// The light vertex of a next-event sample.
BdptVertex lightVertexOf(const Scene& scene, const LightSample& ls);

// The camera's density of the direction of a camera ray (solid angle): film positions uniform
// over the width x height image, ppu^2 / (W H cos^3) with ppu the pixels per unit length of
// the image plane at distance 1.
inline float cameraDirectionDensity(const Camera& camera, int width, int height, Vec3 direction) {
  const float c = camera.cosToAxis(direction);
  if (!(c > 0)) return 0.0f;
  const float ppu = camera.pixelsPerPlaneUnit();
  return ppu * ppu / (float(width) * float(height) * c * c * c);
}

}  // namespace erpt
