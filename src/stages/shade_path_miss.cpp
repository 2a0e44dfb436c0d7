#include "stages/shade_path_miss.h"

#include "kernels/environment_map_lanes.h"
#include "kernels/kernels.h"
#include "kernels/lane_gather.h"
#include "kernels/surface_vertex.h"

namespace erpt {

void finishEnvironmentMiss(const StageContext& ctx, PathQueue& paths, PathSlotQueue& slots, const RayQueue& rays,
                           VertexHistory history, size_t k, const Emitter& env, Color radiance, float lightPdf) {
  const uint32_t id = slots.path[k];
  const Color throughput = paths.throughputAt(id);
  const float w = emitterHitWeight(paths.prevPdf[id], lightPdf);
  paths.radianceSet(id, paths.radianceAt(id) + throughput * radiance * w);
  if (history.vertices == nullptr) return;
  const Vec3 dir = rays.dirAt(k);
  VertexQueue::Row v;  // the whole row: pdfForward 0 and the parent link are written too
  v.p = environmentPoint(paths.prevAt(id), dir);
  v.ns = v.ng = -dir;
  v.kind = kEnvironmentVertex;
  v.emitter = int32_t(&env - ctx.scene.emitters.data());
  v.parent = paths.lastVertex[id];
  history.vertices->setRow(history.base + k, v);
  slots.emitWeight[k] = w;
  slots.emitSet(k, throughput * radiance);
}

EnvironmentMissPacket::EnvironmentMissPacket(const StageContext& ctx) {
  const Emitter* env = ctx.lights.sampledEnvironment();
  if (env == nullptr || env != ctx.scene.environment() || !env->map) return;
  env_ = env;
  map_ = env->map.get();
  probability_ = ctx.lights.pickProbabilityOfEmitter(int(env - ctx.scene.emitters.data()));
}

void EnvironmentMissPacket::shade(const StageContext& ctx, PathQueue& paths, PathSlotQueue& slots,
                                  const RayQueue& rays, VertexHistory history) {
  using namespace lanes3;
  if (count_ == 0) return;
  constexpr size_t kLanes = batch::size;
  static_assert(kCapacity % kLanes == 0, "a packet is whole batches");
  for (size_t j = count_; j % kLanes != 0; ++j) slot_[j] = slot_[0];  // computed, never used
  const EnvironmentMap::Tables tables = map_->tables();
  for (size_t i = 0; i < count_; i += kLanes) {
    const indices slot = indices::load_aligned(&slot_[i]);
    const V3 dir{gatherLanes(rays.dirX.data(), slot), gatherLanes(rays.dirY.data(), slot),
                 gatherLanes(rays.dirZ.data(), slot)};
    batch pdf;
    const V3 radiance = environmentEvalAndPdfLanes(tables, dir, pdf);
    radiance.x.store_aligned(&radiance_[0][i]);
    radiance.y.store_aligned(&radiance_[1][i]);
    radiance.z.store_aligned(&radiance_[2][i]);
    pdf.store_aligned(&pdf_[i]);
  }
  for (size_t j = 0; j < count_; ++j)
    finishEnvironmentMiss(ctx, paths, slots, rays, history, size_t(slot_[j]), *env_,
                          Color(radiance_[0][j], radiance_[1][j], radiance_[2][j]), probability_ * pdf_[j]);
  count_ = 0;
}

}  // namespace erpt
