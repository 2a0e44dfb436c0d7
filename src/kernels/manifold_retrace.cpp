#include "kernels/manifold_retrace.h"

#include <algorithm>
#include <cmath>

#include "kernels/manifold_surface.h"
#include "models/surface.h"

namespace erpt {

namespace {

DVec3 d3(Vec3 v) { return {v.x, v.y, v.z}; }
Vec3 f3(DVec3 v) { return Vec3(float(v.x), float(v.y), float(v.z)); }
double norm(DVec3 a) { return std::sqrt(dot(a, a)); }
DVec3 unit(DVec3 a) { return a * (1.0 / norm(a)); }

// How far along a ray leaving a chain's vertex the tracer starts looking: past the vertex's own
// surface, which its float origin may lie a rounding error below (hits are then made exact in
// double precision, so the ray need not be pushed off the surface).
float startDistance(DVec3 p) { return float(1e-4 * std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z), 1e-2})); }

}  // namespace

double manifoldTolerance(DVec3 p) {
  const double scale = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z), 1e-2});
  return 1e-6 * scale;
}

bool manifoldVertexAlong(const Scene& scene, uint32_t primitive, DVec3 o, DVec3 d, double tHint, ManifoldVertex& out) {
  if (primitive < scene.mesh.triangleCount()) {
    const TriangleSoup& mesh = scene.mesh;
    if (scene.materials[size_t(mesh.material[primitive])].shadingMap != ShadingMap::None) return false;
    const DVec3 p0 = d3(mesh.position(mesh.v0[primitive])), e1 = d3(mesh.position(mesh.v1[primitive])) - p0,
                e2 = d3(mesh.position(mesh.v2[primitive])) - p0;
    const DVec3 face = cross(e1, e2);
    const double den = dot(d, face);
    if (!(std::abs(den) > 0)) return false;
    const DVec3 rel = o + d * (dot(p0 - o, face) / den) - p0;
    // The barycentrics of the point on the triangle's plane (least squares in its edges).
    const double g11 = dot(e1, e1), g12 = dot(e1, e2), g22 = dot(e2, e2), det = g11 * g22 - g12 * g12;
    if (!(det > 0)) return false;
    const double r1 = dot(rel, e1), r2 = dot(rel, e2);
    const double b1 = (g22 * r1 - g12 * r2) / det, b2 = (g11 * r2 - g12 * r1) / det;
    out = manifoldTriangleVertex(mesh, primitive, b1, b2);
    out.hitU = float(b1);
    out.hitV = float(b2);
  } else if (scene.isSphere(primitive)) {
    const SphereSet& spheres = scene.spheres;
    const uint32_t i = scene.sphereOf(primitive);
    const DVec3 oc = o - d3(spheres.center(i));
    const double r = spheres.radius[i], b = dot(oc, d), disc = b * b - (dot(oc, oc) - r * r);
    // The root nearest the tracer's; at a grazing hit the closest approach.
    double t = -b;
    if (disc > 0) {
      const double h = std::sqrt(disc);
      t = std::abs(-b - h - tHint) <= std::abs(-b + h - tHint) ? -b - h : -b + h;
    }
    out = manifoldSphereVertex(spheres, i, o + d * t);
    sphereCoordinates(spheres, i, f3(out.p), out.hitU, out.hitV);
  } else {
    return false;  // instanced triangles: their prototypes' normals live in group space
  }
  out.primitive = primitive;
  return true;
}

void StreamRetracer::trace(size_t count) {
  if (count == 0) return;
  rays_ += count;
  tracer_.intersect(queue_, hits_, IndexRange{0, count}, RayCoherence::Incoherent);
}

void StreamRetracer::locate(std::vector<ManifoldChain>& chains, size_t count, std::vector<uint8_t>& ok) {
  size_t segments = 0;
  for (size_t k = 0; k < count; ++k) segments += chains[k].size() - 1;
  prepareRays(queue_, segments);
  hits_.resize(segments);
  directions_.resize(segments);
  size_t row = 0;
  for (size_t k = 0; k < count; ++k) {
    for (size_t j = 0; j + 1 < chains[k].size(); ++j, ++row) {
      const DVec3 p = chains[k][j].p;
      directions_[row] = unit(chains[k][j + 1].p - p);
      setRay(queue_, row, f3(p), f3(directions_[row]), startDistance(p), std::numeric_limits<float>::infinity());
    }
  }
  trace(segments);
  row = 0;
  ok.assign(count, 1);
  for (size_t k = 0; k < count; ++k) {
    ManifoldChain& chain = chains[k];
    // Rows are in chain order, and vertex j + 1's ray started from the point sought for
    // vertex j, which this loop has already replaced: keep it until then.
    DVec3 origin = chain[0].p;
    for (size_t j = 0; j + 1 < chain.size(); ++j, ++row) {
      const DVec3 sought = chain[j + 1].p;
      ManifoldVertex hit;
      if (hits_.geomID[row] == kNoHit || hits_.geomID[row] == kRefusedRay ||
          !manifoldVertexAlong(scene_, hits_.primID[row], origin, directions_[row], queue_.tfar[row], hit) ||
          norm(hit.p - sought) > 100 * manifoldTolerance(sought)) {
        ok[k] = 0;
      } else {
        hit.reflect = chain[j + 1].reflect;
        hit.eta = chain[j + 1].eta;
        chain[j + 1] = hit;
      }
      origin = sought;
    }
  }
}

void StreamRetracer::retrace(size_t count) {
  prepareRays(queue_, count);
  hits_.resize(count);
  ok_.assign(count, 1);
  directions_.resize(count);
  from_.resize(count);
  if (trials_.size() < count) trials_.resize(count);
  for (size_t k = 0; k < count; ++k) {
    trials_[k].assign(1, shapes_[k]->front());
    from_[k] = shapes_[k]->front().p;
    setRay(queue_, k, f3(from_[k]), f3(directions_[k]), startDistance(from_[k]), std::numeric_limits<float>::infinity());
  }
  // Pass j traces every chain's ray towards its vertex j; a chain that failed, or ended, keeps
  // its row disabled.
  size_t longest = 0;
  for (size_t k = 0; k < count; ++k) longest = std::max(longest, shapes_[k]->size());
  for (size_t j = 1; j < longest; ++j) {
    trace(count);
    for (size_t k = 0; k < count; ++k) {
      const ManifoldChain& shape = *shapes_[k];
      if (!ok_[k] || j >= shape.size() || !(queue_.tnear[k] <= queue_.tfar[k])) continue;
      ManifoldVertex hit;
      if (hits_.geomID[k] == kNoHit || hits_.geomID[k] == kRefusedRay ||
          !manifoldVertexAlong(scene_, hits_.primID[k], from_[k], directions_[k], queue_.tfar[k], hit) ||
          hit.surface != shape[j].surface) {
        ok_[k] = 0;
        disableRay(queue_, k);
        continue;
      }
      hit.reflect = shape[j].reflect;  // the chain's interaction, of the surface's possible ones
      hit.eta = shape[j].eta;
      trials_[k].push_back(hit);
      DVec3 next;
      if (j + 1 == shape.size()) {
        disableRay(queue_, k);
      } else if (!scatterAtManifoldVertex(hit, directions_[k], next)) {
        ok_[k] = 0;
        disableRay(queue_, k);
      } else {
        directions_[k] = unit(next);
        from_[k] = hit.p;
        setRay(queue_, k, f3(from_[k]), f3(directions_[k]), startDistance(from_[k]),
               std::numeric_limits<float>::infinity());
      }
    }
  }
}

void StreamRetracer::walk(const std::vector<ManifoldWalk*>& walks) {
  for (;;) {
    going_.clear();
    shapes_.clear();
    directions_.clear();
    for (ManifoldWalk* w : walks) {
      DVec3 d;
      if (!manifoldWalkAim(*w, d)) continue;
      going_.push_back(w);
      shapes_.push_back(&w->chain);
      directions_.push_back(unit(d));
    }
    if (going_.empty()) return;
    retrace(going_.size());
    for (size_t k = 0; k < going_.size(); ++k) manifoldWalkTake(*going_[k], ok_[k] != 0, trials_[k]);
  }
}

}  // namespace erpt
