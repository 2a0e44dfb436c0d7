// The path tracer's shade stage for its commonest hit, in vector lanes: a path tracer spends
// most of its shading on plain diffuse triangles lit by area lights, and the scalar body
// (stageShadePath) runs their surface reconstruction, light sample, BSDF evaluation, MIS
// weight and cosine-weighted bounce one path at a time, each a chain of dependent divisions,
// square roots and sin/cos. A packet collects such slots (their queue indices), then gathers
// their inputs in the lanes and shades them all with xsimd, 8 paths per instruction with AVX2,
// and scatters the results: the same estimator as the scalar body, the same random numbers,
// rounding aside.
#pragma once

#include <cstddef>
#include <cstdint>

#include "stages/stages.h"

namespace erpt {

class DiffuseShadePacket {
 public:
  static constexpr size_t kCapacity = 64;

  // Takes slot k when its hit qualifies: a non-emitting mesh triangle whose
  // material is diffuse without textures or frame maps, below the depth limit, and the light
  // choice of its random numbers falls on a triangle, a sphere or the environment. False: the
  // scalar body shades it.
  bool add(const StageContext& ctx, const PathQueue& paths, const PathSlotQueue& slots, const HitQueue& hits,
           size_t k);
  bool full() const { return count_ == kCapacity; }
  // Shades every slot taken and empties the packet. When recording seeds, also writes each
  // hit to the vertex history and fills the slot's seed columns, as stageShadePath does.
  void shade(const StageContext& ctx, PathQueue& paths, PathSlotQueue& slots, RayQueue& rays, const HitQueue& hits,
             RayQueue& shadowRays, VertexHistory history);

 private:
  // What add() decides or has at hand, one row per slot taken. The rest of the inputs (the
  // hit, the triangle's corners and normals, the ray, the throughput, the light) shade()
  // gathers from their queues in the lanes, by these indices.
  alignas(64) int32_t slot_[kCapacity] = {};      // the slot in the ray, hit and slot queues
  alignas(64) int32_t path_[kCapacity] = {};      // its path in the path queue
  alignas(64) int32_t triangle_[kCapacity] = {};  // the triangle hit
  alignas(64) int32_t light_[kCapacity] = {};     // the light's row in LightSampler::packetLights()
  enum In {
    kSmooth,  // 1: interpolate the vertex normals
    kLightKind,  // the light's PacketLightKind
    kReflectanceR, kReflectanceG, kReflectanceB,
    kTwoSided,
    kULight1, kULight2, kUBsdf1, kUBsdf2,  // drawn in lanes from drawOffset_, in this order
    kInCount
  };
  enum Out {
    kNeeOk, kNeeR, kNeeG, kNeeB,  // the next-event contribution, throughput included
    kShadowOx, kShadowOy, kShadowOz, kShadowDx, kShadowDy, kShadowDz, kShadowTfar,
    kBounceOk, kNextR, kNextG, kNextB, kBsdfPdf,  // throughput after the bounce, before roulette
    kPx, kPy, kPz,                                // the hit point
    kRayOx, kRayOy, kRayOz, kRayDx, kRayDy, kRayDz,
    // What seed recording keeps of the hit and its connection.
    kNgx, kNgy, kNgz, kNsx, kNsy, kNsz, kNeeMis, kNeeBsdfPdf, kLightPx, kLightPy, kLightPz, kLightNx, kLightNy,
    kLightNz, kNeeLightPdf,
    kOutCount
  };
  alignas(64) float in_[kInCount][kCapacity] = {};
  alignas(64) float out_[kOutCount][kCapacity] = {};
  // The four numbers drawn in lanes (uniformFloatsAt), as their streams' dimensionOffset.
  static constexpr int kLaneDraws = 4;
  static constexpr BounceDim kLaneDrawDims[kLaneDraws] = {kLight1, kLight2, kBsdf1, kBsdf2};
  uint64_t drawOffset_[kLaneDraws][kCapacity] = {};
  double roulette_[kCapacity] = {};
  bool replayed_ = false;  // the lane draws were taken from a chain's primary samples by add()  // the Russian-roulette coin, compared in double as the scalar body does
  size_t count_ = 0;
};

}  // namespace erpt
