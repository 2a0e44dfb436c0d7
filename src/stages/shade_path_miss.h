// The path tracer's escaping rays under an environment map, in vector lanes: each needs the
// map's radiance and its light-sampling density along the ray (for the MIS weight), which
// EnvironmentMap::evalAndPdf computes with an arc tangent, an arc cosine and two bilinear
// lookups. A packet collects such slots and looks their directions up eight at a time
// (kernels/environment_map_lanes.h); finishEnvironmentMiss then adds each one's light as the
// scalar body does.
#pragma once

#include <cstddef>
#include <cstdint>

#include "stages/stages.h"

namespace erpt {

// The far point standing in for the environment along a direction, in recorded seed vertices.
inline Vec3 environmentPoint(Vec3 from, Vec3 dir) { return from + dir * 1e6f; }

// The end of a path that escaped along its ray in slot k: `radiance` arriving from the
// environment `env` along it, weighted against light sampling's solid-angle density
// `lightPdf`; with a vertex history, the environment vertex and the slot's seed columns too.
void finishEnvironmentMiss(const StageContext& ctx, PathQueue& paths, PathSlotQueue& slots, const RayQueue& rays,
                           VertexHistory history, size_t k, const Emitter& env, Color radiance, float lightPdf);

class EnvironmentMissPacket {
 public:
  static constexpr size_t kCapacity = 64;

  // Lanes apply when the environment is the light sampler's and has a map (a constant one
  // needs no lookup).
  explicit EnvironmentMissPacket(const StageContext& ctx);
  bool active() const { return map_ != nullptr; }
  void add(size_t k) { slot_[count_++] = int32_t(k); }
  bool full() const { return count_ == kCapacity; }
  // Finishes every slot taken and empties the packet.
  void shade(const StageContext& ctx, PathQueue& paths, PathSlotQueue& slots, const RayQueue& rays,
             VertexHistory history);

 private:
  const Emitter* env_ = nullptr;
  const EnvironmentMap* map_ = nullptr;
  float probability_ = 0;  // the environment's pick probability among the lights
  alignas(64) int32_t slot_[kCapacity] = {};
  alignas(64) float radiance_[3][kCapacity] = {};
  alignas(64) float pdf_[kCapacity] = {};
  size_t count_ = 0;
};

}  // namespace erpt
