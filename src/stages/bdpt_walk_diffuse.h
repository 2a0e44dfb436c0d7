// BDPT's walks at their commonest vertex, in vector lanes: a plain diffuse triangle, where the
// scalar walk (stageBdptExtend) rebuilds the surface point and its frame, samples the cosine
// lobe, converts the densities of both directions to area measure and weighs the bounce (with
// the adjoint BSDF from the light side), one walk at a time. A packet collects such walks (their
// slot indices and what add() reads of them), computes their geometry, bounce and densities
// eight at a time with xsimd, and writes the vertices and the walks' next rays as the scalar
// walk does: the same estimator and random numbers, rounding aside.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "stages/bdpt_stages.h"

namespace erpt {

class BdptDiffuseWalkPacket {
 public:
  static constexpr size_t kCapacity = 64;

  // Takes walk k when its ray hit a mesh triangle whose material is diffuse without textures
  // or frame maps. False: the scalar walk extends it.
  bool add(const BdptContext& ctx, BdptSide side, const BdptSubpaths& paths, const BdptWalkQueue& walks,
           const HitQueue& hits, size_t k);
  bool full() const { return count_ == kCapacity; }
  // Extends every walk taken (as stageBdptExtend: vertices[base + k], the ray in place,
  // alive[k]) and empties the packet.
  void extend(const BdptContext& ctx, BdptSide side, BdptSubpaths& paths, BdptWalkQueue& walks, RayQueue& rays,
              const HitQueue& hits, size_t base, std::vector<uint8_t>& alive);

 private:
  alignas(64) int32_t slot_[kCapacity] = {};      // the walk
  alignas(64) int32_t triangle_[kCapacity] = {};  // the triangle hit
  alignas(64) int32_t previous_[kCapacity] = {};  // the walk's newest vertex before this one
  enum In {
    kSmooth, kTwoSided,  // 1 or 0
    kReflectanceR, kReflectanceG, kReflectanceB,
    kPrevAtInfinity,  // 1: the previous vertex is the environment (a direction, no point)
    kUBsdf1, kUBsdf2,
    kInCount
  };
  enum Out {
    kPx, kPy, kPz, kNgx, kNgy, kNgz, kNsx, kNsy, kNsz,
    kPdfForward,  // this vertex's area density from the previous one
    kCosIn,       // |cos| of the arriving ray at the geometric normal
    kBounceOk,
    kWeightR, kWeightG, kWeightB,  // the bounce's weight (adjoint from the light side)
    kPdfNext,                      // the bounce's solid-angle density
    kPdfReverse,                   // the previous vertex's area density sampled from here
    kRayOx, kRayOy, kRayOz, kRayDx, kRayDy, kRayDz,
    kOutCount
  };
  alignas(64) float in_[kInCount][kCapacity] = {};
  alignas(64) float out_[kOutCount][kCapacity] = {};
  double roulette_[kCapacity] = {};  // the Russian-roulette coin (compared in double, as the scalar walk does)
  bool bounces_[kCapacity] = {};     // below the depth limit and the strategy's cap
  size_t count_ = 0;
};

}  // namespace erpt
