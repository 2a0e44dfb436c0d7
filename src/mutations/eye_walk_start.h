// The start shared by the units that move the film position and walk from the eye (the lens
// perturbations and the manifold perturbation): the film offset, the walk's plan, and the eye
// rays, made by the camera's vector kernel in batches (a scalar camera ray is a chain of
// dependent divisions and square roots).
#pragma once

#include <cmath>

#include "core/rng.h"
#include "models/camera.h"
#include "mutations/mutation.h"

namespace erpt {

// Film positions a little outside the square or disk by rounding still count as inside.
constexpr float kFilmSlack = 1e-3f;

// Film positions of the two shapes: uniform in the square of half-side `size`, or in the
// disk of radius `size` (radius size * sqrt(u1), angle 2 pi u2).
inline void squareOffset(float size, float u1, float u2, float& dx, float& dy) {
  dx = (2 * u1 - 1) * size;
  dy = (2 * u2 - 1) * size;
}

inline void diskOffset(float size, float u1, float u2, float& dx, float& dy) {
  const float r = size * std::sqrt(u1), phi = 2 * kPi * u2;
  dx = r * std::cos(phi);
  dy = r * std::sin(phi);
}

// The eye rays of a batch of lens starts. A scalar camera ray is a chain of dependent
// divisions and square roots; the camera's vector kernel makes a batch of them at once.
class EyeRayBatch {
 public:
  EyeRayBatch(const Camera& camera, const VertexQueue& chainVertices, RayQueue& rays)
      : camera_(camera), chainVertices_(chainVertices), rays_(rays) {}

  void add(size_t slot, float filmX, float filmY) {
    slot_[count_] = slot;
    filmX_[count_] = filmX;
    filmY_[count_] = filmY;
    if (++count_ == kSize) flush();
  }

  void flush() {
    if (count_ == 0) return;
    float dx[kSize], dy[kSize], dz[kSize], tnear[kSize], tfar[kSize];
    camera_.generateRays(filmX_, filmY_, count_, dx, dy, dz, tnear, tfar);
    for (size_t b = 0; b < count_; ++b) {
      Camera::Ray r{camera_.position(), Vec3(dx[b], dy[b], dz[b]), tnear[b], tfar[b]};
      // From the chain's lens point (vertex 0), which stays fixed.
      if (camera_.hasLens()) r = camera_.refocus(chainVertices_.pAt(slot_[b] * kMaxChainVertices), r);
      setRay(rays_, slot_[b], r.origin, r.direction, r.tnear, r.tfar);
    }
    count_ = 0;
  }

 private:
  static constexpr size_t kSize = 64;

  const Camera& camera_;
  const VertexQueue& chainVertices_;
  RayQueue& rays_;
  size_t slot_[kSize];
  float filmX_[kSize], filmY_[kSize];
  size_t count_ = 0;
};

// Every start of `kind` in a range: the new film position (Offset), the walk's plan (Plan: the
// last regenerated vertex and the connection target from the packed signature; false rejects),
// and the eye ray.
template <auto Offset, auto Plan>
void startEyeWalks(MutationKind kind, const StepConfig& ctx, const ChainQueue& chains, const VertexQueue& chainVertices,
                    ProposalQueue& proposals, RayQueue& rays, IndexRange range) {
  const MeasureContext& c = ctx.measure;
  EyeRayBatch eyeRays(c.camera, chainVertices, rays);
  for (size_t i = range.begin; i < range.end; ++i) {
    if (proposals.mutation[i] != uint8_t(kind) || proposals.state[i] != kProposalWalking) continue;
    const uint64_t key = chains.key[i];
    const uint32_t step = chains.step[i];
    float dx, dy;
    Offset(proposals.perturbSize[i], uniformFloat(key, stepDim(step, kDimStart1)),
           uniformFloat(key, stepDim(step, kDimStart2)), dx, dy);
    const float fx = chains.filmX[i] + dx, fy = chains.filmY[i] + dy;
    proposals.filmX[i] = fx;
    proposals.filmY[i] = fy;
    if (!(c.film.density(fx, fy) > 0)) {
      rejectProposal(proposals, rays, i, kRejectOffFilm);
      continue;
    }
    int regenLast, connectTo;
    if (!Plan(chains.signature[i], int(chains.vertexCount[i]), regenLast, connectTo)) {
      rejectProposal(proposals, rays, i, kRejectNoMutation);
      continue;
    }
    proposals.cursor[i] = 1;
    proposals.walk[i] = +1;
    proposals.regenFirst[i] = 1;
    proposals.regenLast[i] = int8_t(regenLast);
    proposals.connectTo[i] = int8_t(connectTo);
    eyeRays.add(i, fx, fy);
  }
  eyeRays.flush();
}

// Whether film positions y and z lie within `size` of each other in a disk (the manifold and
// lens-disk perturbations' T, 1 / (pi size^2) both ways).
inline bool withinDisk(const CurrentPath& y, const CurrentPath& z, float size) {
  const float dx = y.filmX - z.filmX, dy = y.filmY - z.filmY;
  return std::sqrt(dx * dx + dy * dy) <= size + kFilmSlack;
}

}  // namespace erpt
