// The manifold walk's rays through the scene's tracer, for many chains at once: every pass
// hands Embree one ray of each chain still going, as a stream (the walk itself, per chain, is
// kernels/manifold_walk.h). A chain's vertices come from the tracer's hits with the shapes'
// curvature (kernels/manifold_surface.h), in double precision from there on.
#pragma once

#include <cstdint>
#include <vector>

#include "kernels/manifold_walk.h"
#include "tracer/tracer.h"

namespace erpt {

// The walk's vertex where the ray o + t d (d unit) meets `primitive`, which the scene's tracer
// found near t = tHint: intersected again in double precision (the tracer's float hit would
// limit the walk to about 1e-4 of the scene's size), with the surface's curvature, and its
// hit coordinates for the renderer's own surface point (surfaceAt). False for what the walk
// cannot differentiate: instanced triangles and materials with normal or bump maps.
bool manifoldVertexAlong(const Scene& scene, uint32_t primitive, DVec3 o, DVec3 d, double tHint, ManifoldVertex& out);

// How close a walk must bring its endpoint to its target (a float point of the renderer's,
// whose rounding it must allow), relative to the size of the coordinates; a retraced vertex
// within 100 tolerances of a stored one is taken for it.
double manifoldTolerance(DVec3 p);

class StreamRetracer {
 public:
  StreamRetracer(const Tracer& tracer, const Scene& scene) : tracer_(tracer), scene_(scene) {}

  // Finds the chains the renderer already holds, with the walk's data. chains[k][0] is the
  // fixed end as the caller describes it; its other vertices are sought where their `p` says,
  // by rays from each point to the next (one pass for all segments), and replaced by what the
  // rays hit, keeping the `reflect` and `eta` the caller gave them. ok[k]: every segment hit a
  // surface the walk can differentiate, within 100 manifoldTolerance of the point sought.
  void locate(std::vector<ManifoldChain>& chains, size_t count, std::vector<uint8_t>& ok);

  // Runs every walk to its end (startManifoldWalk already called): each Newton step of all the
  // walks still going is one batch of retraces, a pass per vertex of their chains.
  void walk(const std::vector<ManifoldWalk*>& walks);

  uint64_t raysTraced() const { return rays_; }

 private:
  // Retraces chain k < count from shapes_[k]->front() along directions_[k] by the chain's
  // interactions: trials_[k], ok_[k] when it met the same surfaces in order.
  void retrace(size_t count);
  // Traces rays_[0, count) into hits_.
  void trace(size_t count);

  const Tracer& tracer_;
  const Scene& scene_;
  RayQueue queue_;
  HitQueue hits_;
  uint64_t rays_ = 0;
  // Scratch of the walks' retraces (kept between calls: a step allocates nothing once warm).
  std::vector<ManifoldWalk*> going_;
  std::vector<const ManifoldChain*> shapes_;
  std::vector<DVec3> directions_, from_;
  std::vector<ManifoldChain> trials_;
  std::vector<uint8_t> ok_;
};

}  // namespace erpt
