// The only file that includes Embree.
#include <embree3/rtcore.h>

#include <atomic>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <vector>

#include "kernels/sphere_coordinates.h"
#include "models/surface.h"
#include "tracer/tracer.h"
#include "untraceable_rays.h"

namespace erpt {

namespace {
void onEmbreeError(void*, RTCError code, const char* message) {
  if (code != RTC_ERROR_NONE) std::fprintf(stderr, "embree error %d: %s\n", int(code), message ? message : "");
}
}  // namespace

struct Tracer::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::vector<RTCScene> groupScenes;  // one per instanced shapegroup
  std::vector<float> prototypeVertices;  // shared by the groups' geometries (x, y, z, pad)
  const SphereSet* spheres = nullptr;
  mutable std::atomic<uint64_t> refused{0};  // rays refused so far (untraceable_rays.h)

  // Disables the untraceable rays of a batch and returns their indices (this thread's list,
  // valid until its next call); the shared count is touched only when there are some.
  const std::vector<uint32_t>& refuse(RayQueue& rays, IndexRange range) const {
    thread_local std::vector<uint32_t> indices;
    indices.clear();
    if (const size_t n = refuseUntraceableRays(rays, range, indices)) refused += n;
    return indices;
  }
  unsigned sphereGeometry = RTC_INVALID_GEOMETRY_ID;
  unsigned firstSpherePrimitive = 0;
  const InstanceSet* instances = nullptr;
  unsigned firstInstanceGeometry = RTC_INVALID_GEOMETRY_ID;

  // Embree names a hit by (instance, geometry, primitive in it); the renderer by one
  // primitive id (scene.h) and, for a sphere, the sphere coordinates of the hit point
  // (surface.h).
  void toScenePrimitives(const RayQueue& rays, HitQueue& hits, IndexRange range) const {
    if (instances) {
      for (size_t i = range.begin; i < range.end; ++i) {
        if (hits.instID[i] == RTC_INVALID_GEOMETRY_ID) continue;
        hits.primID[i] += instances->firstPrimitive[hits.instID[i] - firstInstanceGeometry];
        hits.geomID[i] = hits.instID[i];
      }
    }
    if (sphereGeometry == RTC_INVALID_GEOMETRY_ID) return;
    // Each sphere hit's point in its sphere's frame, then the coordinates of a batch of them
    // in vector lanes (sphereCoordinates' math).
    constexpr size_t kBatch = 64;
    uint32_t row[kBatch];
    float x[kBatch], y[kBatch], z[kBatch], u[kBatch], v[kBatch];
    size_t count = 0;
    auto flush = [&] {
      sphereCoordinatesOf(x, y, z, count, u, v);
      for (size_t b = 0; b < count; ++b) hits.u[row[b]] = u[b], hits.v[row[b]] = v[b];
      count = 0;
    };
    for (size_t i = range.begin; i < range.end; ++i) {
      if (hits.geomID[i] != sphereGeometry) continue;
      const uint32_t sphere = hits.primID[i];
      const Vec3 o = rays.orgAt(i), d = rays.dirAt(i);
      const float t = refineSphereHit(*spheres, sphere, o, d, rays.tfar[i]);
      const Vec3 local = spheres->frame[sphere].toLocal(o + d * t - spheres->center(sphere));
      row[count] = uint32_t(i);
      x[count] = local.x, y[count] = local.y, z[count] = local.z;
      if (++count == kBatch) flush();
      hits.primID[i] = firstSpherePrimitive + sphere;
    }
    if (count > 0) flush();
  }
};

namespace {
void attachSpheres(RTCDevice device, RTCScene scene, const SphereSet& spheres) {
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
  auto* points = static_cast<float*>(
      rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), spheres.count()));
  for (uint32_t i = 0; i < spheres.count(); ++i) {
    points[4 * i] = spheres.cx[i];
    points[4 * i + 1] = spheres.cy[i];
    points[4 * i + 2] = spheres.cz[i];
    points[4 * i + 3] = spheres.radius[i];
  }
  rtcCommitGeometry(geom);
  rtcAttachGeometry(scene, geom);
  rtcReleaseGeometry(geom);
}

void rejectCutOutHits(const RTCFilterFunctionNArguments* args);

// `mesh`'s vertices as Embree reads them: x, y, z and a pad. (Embree may read 16 bytes from
// the last vertex: its own buffers are padded for that, a shared one needs a spare vertex.)
void fillVertices(const TriangleSoup& mesh, float* vertices) {
  for (size_t i = 0; i < mesh.vertexCount(); ++i) {
    vertices[4 * i] = mesh.px[i];
    vertices[4 * i + 1] = mesh.py[i];
    vertices[4 * i + 2] = mesh.pz[i];
    vertices[4 * i + 3] = 0;
  }
}

// Triangles `first` .. first + count - 1 of `mesh` as one Embree triangle geometry of
// `scene`, with its own vertex buffer or `sharedVertices` (fillVertices' layout).
void attachTriangles(RTCDevice device, RTCScene scene, const TriangleSoup& mesh, size_t first, size_t count,
                     const Scene* masks, const float* sharedVertices = nullptr) {
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  if (sharedVertices) {
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, sharedVertices, 0,
                               4 * sizeof(float), mesh.vertexCount());
  } else {
    fillVertices(mesh, static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                   4 * sizeof(float), mesh.vertexCount())));
  }
  auto* indices = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), count));
  for (size_t t = 0; t < count; ++t) {
    indices[3 * t] = mesh.v0[first + t];
    indices[3 * t + 1] = mesh.v1[first + t];
    indices[3 * t + 2] = mesh.v2[first + t];
  }
  if (masks) {
    // `mask` cut-outs: hits where the opacity is below 0.5 are rejected for every ray.
    rtcSetGeometryUserData(geom, const_cast<Scene*>(masks));
    rtcSetGeometryIntersectFilterFunction(geom, rejectCutOutHits);
    rtcSetGeometryOccludedFilterFunction(geom, rejectCutOutHits);
  }
  rtcCommitGeometry(geom);
  rtcAttachGeometry(scene, geom);
  rtcReleaseGeometry(geom);
}

// Each instance as an Embree instance of its group's scene, placed by its to_world.
void attachInstances(RTCDevice device, RTCScene scene, const InstanceSet& in, std::vector<float>& vertices,
                     std::vector<RTCScene>& groupScenes) {
  vertices.assign(4 * (in.prototypes.vertexCount() + 1), 0.0f);
  fillVertices(in.prototypes, vertices.data());
  for (size_t g = 0; g < in.groupCount(); ++g) {
    RTCScene group = rtcNewScene(device);
    rtcSetSceneBuildQuality(group, RTC_BUILD_QUALITY_HIGH);
    attachTriangles(device, group, in.prototypes, in.groupFirstTriangle[g], in.groupTriangleCount[g], nullptr,
                    vertices.data());
    rtcCommitScene(group);
    groupScenes.push_back(group);
  }
  for (size_t k = 0; k < in.count(); ++k) {
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(geom, groupScenes[in.group[k]]);
    float rows[12];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) rows[4 * r + c] = float(in.toWorld[k](r, c));
    rtcSetGeometryTransform(geom, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, rows);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
  }
}

// Embree intersection filter (N rays at once): rejects candidate hits on the cut-out part of
// a `mask` material, so traversal goes on behind them.
void rejectCutOutHits(const RTCFilterFunctionNArguments* args) {
  const Scene& scene = *static_cast<const Scene*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const unsigned triangle = RTCHitN_primID(args->hit, args->N, i);
    if (!scene.opaqueAt(triangle, RTCHitN_u(args->hit, args->N, i), RTCHitN_v(args->hit, args->N, i))) args->valid[i] = 0;
  }
}

}  // namespace

Tracer::Tracer(const Scene& scene) : impl_(std::make_unique<Impl>()) {
  impl_->device = rtcNewDevice(nullptr);
  if (!impl_->device) throw std::runtime_error("cannot create an Embree device");
  rtcSetDeviceErrorFunction(impl_->device, onEmbreeError, nullptr);
  impl_->scene = rtcNewScene(impl_->device);
  rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_HIGH);
  const TriangleSoup& mesh = scene.mesh;
  // Geometry ids in attachment order: world triangles, spheres, instances.
  unsigned nextGeometry = 0;
  if (mesh.triangleCount() > 0) {
    attachTriangles(impl_->device, impl_->scene, mesh, 0, mesh.triangleCount(), scene.hasMasks() ? &scene : nullptr);
    ++nextGeometry;
  }
  if (scene.spheres.count() > 0) {
    impl_->spheres = &scene.spheres;
    impl_->firstSpherePrimitive = uint32_t(mesh.triangleCount());
    impl_->sphereGeometry = nextGeometry++;
    attachSpheres(impl_->device, impl_->scene, scene.spheres);
  }
  if (scene.instances.count() > 0) {
    impl_->instances = &scene.instances;
    impl_->firstInstanceGeometry = nextGeometry;
    attachInstances(impl_->device, impl_->scene, scene.instances, impl_->prototypeVertices, impl_->groupScenes);
  }
  rtcCommitScene(impl_->scene);
}

Tracer::~Tracer() {
  if (impl_->scene) rtcReleaseScene(impl_->scene);
  for (RTCScene group : impl_->groupScenes) rtcReleaseScene(group);
  if (impl_->device) rtcReleaseDevice(impl_->device);
}

namespace {
RTCRayNp rayColumns(RayQueue& q, size_t b) {
  return RTCRayNp{q.orgX.data() + b, q.orgY.data() + b, q.orgZ.data() + b, q.tnear.data() + b,
                  q.dirX.data() + b, q.dirY.data() + b, q.dirZ.data() + b, q.time.data() + b,
                  q.tfar.data() + b, q.mask.data() + b, q.id.data() + b,   q.flags.data() + b};
}

RTCIntersectContext makeContext(RayCoherence coherence) {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  ctx.flags = coherence == RayCoherence::Coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT
                                                  : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  return ctx;
}
}  // namespace

void Tracer::intersect(RayQueue& rays, HitQueue& hits, IndexRange range, RayCoherence coherence) const {
  if (range.size() == 0) return;
  const std::vector<uint32_t>& refused = impl_->refuse(rays, range);
  size_t b = range.begin;
  for (size_t i = b; i < range.end; ++i) hits.geomID[i] = hits.instID[i] = RTC_INVALID_GEOMETRY_ID;
  RTCRayHitNp rh;
  rh.ray = rayColumns(rays, b);
  rh.hit.Ng_x = hits.ngX.data() + b;
  rh.hit.Ng_y = hits.ngY.data() + b;
  rh.hit.Ng_z = hits.ngZ.data() + b;
  rh.hit.u = hits.u.data() + b;
  rh.hit.v = hits.v.data() + b;
  rh.hit.primID = hits.primID.data() + b;
  rh.hit.geomID = hits.geomID.data() + b;
  rh.hit.instID[0] = hits.instID.data() + b;
  RTCIntersectContext ctx = makeContext(coherence);
  rtcIntersectNp(impl_->scene, &ctx, &rh, unsigned(range.size()));
  impl_->toScenePrimitives(rays, hits, range);
  for (uint32_t i : refused) hits.geomID[i] = kRefusedRay;
}

void Tracer::occluded(RayQueue& rays, IndexRange range) const {
  if (range.size() == 0) return;
  const std::vector<uint32_t>& refused = impl_->refuse(rays, range);
  RTCRayNp r = rayColumns(rays, range.begin);
  RTCIntersectContext ctx = makeContext(RayCoherence::Incoherent);
  rtcOccludedNp(impl_->scene, &ctx, &r, unsigned(range.size()));
  // A refused shadow ray is reported occluded: its connection contributes nothing.
  for (uint32_t i : refused) rays.tfar[i] = -std::numeric_limits<float>::infinity();
}

uint64_t Tracer::refusedRays() const { return impl_->refused.load(); }

namespace {
RTCRay scalarRay(const RayQueue& q, size_t i) {
  RTCRay r;
  r.org_x = q.orgX[i];
  r.org_y = q.orgY[i];
  r.org_z = q.orgZ[i];
  r.tnear = q.tnear[i];
  r.dir_x = q.dirX[i];
  r.dir_y = q.dirY[i];
  r.dir_z = q.dirZ[i];
  r.time = q.time[i];
  r.tfar = q.tfar[i];
  r.mask = q.mask[i];
  r.id = q.id[i];
  r.flags = q.flags[i];
  return r;
}
}  // namespace

void Tracer::intersectOneByOne(RayQueue& rays, HitQueue& hits, IndexRange range) const {
  RTCIntersectContext ctx = makeContext(RayCoherence::Incoherent);
  for (size_t i = range.begin; i < range.end; ++i) {
    RTCRayHit rh;
    rh.ray = scalarRay(rays, i);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(impl_->scene, &ctx, &rh);
    rays.tfar[i] = rh.ray.tfar;
    hits.ngX[i] = rh.hit.Ng_x;
    hits.ngY[i] = rh.hit.Ng_y;
    hits.ngZ[i] = rh.hit.Ng_z;
    hits.u[i] = rh.hit.u;
    hits.v[i] = rh.hit.v;
    hits.primID[i] = rh.hit.primID;
    hits.geomID[i] = rh.hit.geomID;
    hits.instID[i] = rh.hit.instID[0];
  }
  impl_->toScenePrimitives(rays, hits, range);
}

void Tracer::occludedOneByOne(RayQueue& rays, IndexRange range) const {
  RTCIntersectContext ctx = makeContext(RayCoherence::Incoherent);
  for (size_t i = range.begin; i < range.end; ++i) {
    RTCRay r = scalarRay(rays, i);
    rtcOccluded1(impl_->scene, &ctx, &r);
    rays.tfar[i] = r.tfar;
  }
}

}  // namespace erpt
