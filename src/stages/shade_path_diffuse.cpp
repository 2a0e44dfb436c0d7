// The diffuse shade kernel (shade_path_diffuse.h): gather, vector body, scatter. Every
// formula mirrors the scalar code it replaces for these hits: triangleSurfaceAt, Frame,
// LightSampler::sampleTriangle / sampleSphere / finishAreaSample and its environment sample
// (kernels/environment_map_lanes.h), connectToLight, the diffuse lobe of bsdfEval / bsdfPdf /
// bsdfSample, offsetOrigin and the roulette of stageShadePath.
#include "stages/shade_path_diffuse.h"

#include <limits>

#include <xsimd/xsimd.hpp>

#include "core/rng.h"
#include "core/warp.h"
#include "kernels/environment_map_lanes.h"
#include "kernels/lane_gather.h"
#include "kernels/lane_vec3.h"
#include "kernels/surface_lanes.h"
#include "kernels/surface_vertex.h"
#include "kernels/uniform_lanes.h"
#include "models/surface.h"
#include "tracer/tracer.h"

namespace erpt {

namespace {

using namespace lanes3;
using lanes = mask;
constexpr size_t kLanes = batch::size;
static_assert(DiffuseShadePacket::kCapacity % kLanes == 0, "a packet is whole batches");

// A light point of each lane's light: its position, its emitting normal, and (cone) whether
// it was sampled in the cone of directions, whose solid-angle density is coneDensity.
struct LanePacketLight {
  V3 point, normal;
  lanes cone;
  batch coneDensity;
};

// sampleTriangle: the point at barycentrics from the square (squareToTriangle).
void triangleLightPoints(const PacketLightQueue& lights, const indices& light, const batch& u1, const batch& u2,
                         LanePacketLight& out) {
  auto gather3 = [&](const auto& x, const auto& y, const auto& z) {
    return V3{gatherLanes(x.data(), light), gatherLanes(y.data(), light), gatherLanes(z.data(), light)};
  };
  const lanes lower = u1 < u2;
  const batch b1 = xsimd::select(lower, u1 * 0.5f, u1 - u2 * 0.5f);
  const batch b2 = xsimd::select(lower, u2 - u1 * 0.5f, u2 * 0.5f);
  out.point = gather3(lights.aX, lights.aY, lights.aZ) * (1.0f - b1 - b2) + gather3(lights.bX, lights.bY, lights.bZ) * b1 +
              gather3(lights.cX, lights.cY, lights.cZ) * b2;
  out.normal = gather3(lights.normalX, lights.normalY, lights.normalZ);
  out.cone = lanes(false);
  out.coneDensity = batch(0.0f);
}

// sampleSphere: uniform in the cone the sphere subtends at `ref` (sphereCone), the point where
// that direction first meets it; or, from inside or for a sphere that emits inwards, a point
// uniform by area.
void sphereLightPoints(const PacketLightQueue& lights, const indices& light, const V3& ref, const batch& u1,
                       const batch& u2, LanePacketLight& out) {
  const V3 center{gatherLanes(lights.aX.data(), light), gatherLanes(lights.aY.data(), light),
                  gatherLanes(lights.aZ.data(), light)};
  const batch radius = gatherLanes(lights.radius.data(), light);
  const lanes flipped = gatherLanes(lights.flipped.data(), light) != batch(0.0f);
  const V3 toCenter = center - ref;
  const batch dist2 = dot(toCenter, toCenter), r2 = radius * radius;
  const batch sin2Max = r2 / dist2;
  const batch cosMax = xsimd::sqrt(xsimd::max(batch(0.0f), 1.0f - sin2Max));
  const batch coneOutside = sin2Max / (1.0f + cosMax);
  // sphereCone's test; a cone that rounds to 0 (a sphere too small to see) is sampled by area.
  const lanes inCone = ~flipped & (dist2 > r2 * 1.0001f) & (coneOutside > batch(0.0f));
  const batch cone = xsimd::select(inCone, coneOutside, batch(0.0f));
  const auto sc = xsimd::sincos(batch(2 * kPi) * u2);
  // In the cone (the float solve of sampleSphere, cancellation-free near the silhouette).
  const batch dc = xsimd::sqrt(dist2);
  const batch x = u1 * cone, cosTheta = 1.0f - x;
  const batch sinTheta = xsimd::sqrt(xsimd::max(batch(0.0f), x * (2.0f - x)));
  const LaneFrame frame(toCenter / dc);
  const V3 w = frame.toWorld({sinTheta * sc.second, sinTheta * sc.first, cosTheta});
  const batch beyond = cone * (1.0f - u1) * (2.0f - cone - x);
  const batch t = dc * (cosTheta - xsimd::sqrt(xsimd::max(batch(0.0f), beyond)));
  const V3 onRay = ref + w * t - center;
  const V3 coneRadial = onRay / xsimd::sqrt(dot(onRay, onRay));
  // By area (squareToUniformSphere).
  const batch z = 1.0f - 2.0f * u1, r = xsimd::sqrt(xsimd::max(batch(0.0f), 1.0f - z * z));
  const V3 areaRadial{r * sc.second, r * sc.first, z};
  const V3 radial = select(inCone, coneRadial, areaRadial);
  out.point = center + radial * radius;
  out.normal = select(flipped, -radial, radial);
  out.cone = inCone;
  out.coneDensity = gatherLanes(lights.probability.data(), light) / (batch(2 * kPi) * cone);
}

// sample()'s environment: a direction from the map's importance sampling, or uniform on the
// sphere for a constant one (squareToUniformSphere), with its radiance and the map's density.
LaneEnvironmentSample environmentLightDirections(const EnvironmentMap* map, const EnvironmentMap::Tables& tables,
                                                 const PacketLightQueue& lights, const indices& light, const batch& u1,
                                                 const batch& u2) {
  if (map) return sampleEnvironmentLanes(tables, u1, u2);
  const batch z = 1.0f - 2.0f * u1, r = xsimd::sqrt(xsimd::max(batch(0.0f), 1.0f - z * z));
  const auto sc = xsimd::sincos(batch(2 * kPi) * u2);
  return {{r * sc.second, r * sc.first, z},
          {gatherLanes(lights.radianceR.data(), light), gatherLanes(lights.radianceG.data(), light),
           gatherLanes(lights.radianceB.data(), light)},
          batch(kUniformSpherePdf),
          lanes(true)};
}

}  // namespace

bool DiffuseShadePacket::add(const StageContext& ctx, const PathQueue& paths, const PathSlotQueue& slots,
                             const HitQueue& hits, size_t k) {
  const uint32_t geom = hits.geomID[k];
  if (geom == kNoHit || geom == kRefusedRay) return false;
  const TriangleSoup& mesh = ctx.scene.mesh;
  const uint32_t tri = hits.primID[k];
  if (tri >= mesh.triangleCount() || mesh.emitter[tri] >= 0) return false;
  const Material& m = ctx.scene.materials[size_t(mesh.material[tri])];
  if (m.kind != BsdfKind::Diffuse || m.reflectance.texture >= 0 || m.adjustsShadingFrame()) return false;
  const uint32_t id = slots.path[k];
  const uint32_t depth = paths.depth[id];
  if (ctx.maxDepth >= 0 && depth >= uint32_t(ctx.maxDepth)) return false;
  const uint64_t key = paths.key[id];
  uint32_t light;
  if (!ctx.lights.pickPacketLight(drawDouble(ctx, key, bounceDim(depth, kLightPick)), light)) return false;

  const size_t j = count_++;
  slot_[j] = int32_t(k);
  path_[j] = int32_t(id);
  triangle_[j] = int32_t(tri);
  light_[j] = int32_t(light);
  in_[kSmooth][j] = mesh.smooth[tri] != 0 ? 1.0f : 0.0f;
  in_[kLightKind][j] = float(ctx.lights.packetLights().kind[light]);
  in_[kReflectanceR][j] = m.reflectance.value.x;
  in_[kReflectanceG][j] = m.reflectance.value.y;
  in_[kReflectanceB][j] = m.reflectance.value.z;
  in_[kTwoSided][j] = m.twoSided ? 1.0f : 0.0f;
  // The light point's and the bounce's numbers are drawn in lanes by shade(), or here when
  // they are a chain's primary samples.
  replayed_ = ctx.replay != nullptr;
  for (int d = 0; d < kLaneDraws; ++d) {
    if (replayed_) in_[kULight1 + d][j] = drawFloat(ctx, key, bounceDim(depth, kLaneDrawDims[d]));
    else drawOffset_[d][j] = dimensionOffset(key, bounceDim(depth, kLaneDrawDims[d]));
  }
  roulette_[j] = int(depth) >= ctx.rrDepth ? drawDouble(ctx, key, bounceDim(depth, kRoulette)) : 0.0;
  return true;
}

void DiffuseShadePacket::shade(const StageContext& ctx, PathQueue& paths, PathSlotQueue& slots, RayQueue& rays,
                               const HitQueue& hits, RayQueue& shadowRays, VertexHistory history) {
  if (count_ == 0) return;
  if (!replayed_)
    for (int d = 0; d < kLaneDraws; ++d) uniformFloatsAt(drawOffset_[d], count_, in_[kULight1 + d]);
  // Rows past count_, up to a whole batch, gather row 0's queue entries: their lanes are
  // computed and never stored (their other inputs are stale or unset).
  for (size_t j = count_; j % kLanes != 0; ++j)
    slot_[j] = slot_[0], path_[j] = path_[0], triangle_[j] = triangle_[0], light_[j] = light_[0];
  const TriangleSoup& mesh = ctx.scene.mesh;
  const PacketLightQueue& lights = ctx.lights.packetLights();
  const Emitter* environment = ctx.lights.sampledEnvironment();
  const EnvironmentMap* map = environment ? environment->map.get() : nullptr;
  const EnvironmentMap::Tables mapTables = map ? map->tables() : EnvironmentMap::Tables{};
  for (size_t i = 0; i < count_; i += kLanes) {
    auto get = [&](int c) { return batch::load_aligned(&in_[c][i]); };
    auto put = [&](int c, const batch& b) { b.store_aligned(&out_[c][i]); };
    auto put3 = [&](int first, const V3& v) { put(first, v.x), put(first + 1, v.y), put(first + 2, v.z); };
    auto putMask = [&](int c, const lanes& m) { put(c, xsimd::select(m, batch(1.0f), batch(0.0f))); };
    auto gather = [](const auto& column, const indices& at) { return gatherLanes(column.data(), at); };
    auto gather3 = [&](const auto& x, const auto& y, const auto& z, const indices& at) {
      return V3{gather(x, at), gather(y, at), gather(z, at)};
    };
    const indices slot = indices::load_aligned(&slot_[i]), path = indices::load_aligned(&path_[i]);
    const indices triangle = indices::load_aligned(&triangle_[i]), light = indices::load_aligned(&light_[i]);

    // The surface point (triangleSurfaceAt).
    const LaneTriangleHit hit =
        triangleHitLanes(mesh, triangle, gather(hits.u, slot), gather(hits.v, slot), get(kSmooth) != batch(0.0f));
    const V3 position = hit.position, ng = hit.ng;
    const V3 zero{batch(0.0f), batch(0.0f), batch(0.0f)};
    const LaneFrame frame(hit.shading);
    const V3 dir = gather3(rays.dirX, rays.dirY, rays.dirZ, slot);
    const batch wiZ = -dot(dir, frame.n);
    // sideFlip: the front, or the back of a two-sided material seen as its front.
    const batch flip = xsimd::select(wiZ > batch(0.0f), batch(1.0f),
                                     xsimd::select((get(kTwoSided) != batch(0.0f)) & (wiZ < batch(0.0f)), batch(-1.0f),
                                                   batch(0.0f)));
    const lanes seen = flip != batch(0.0f);
    const V3 throughput = gather3(paths.throughputR, paths.throughputG, paths.throughputB, path);
    const V3 reflectance{get(kReflectanceR), get(kReflectanceG), get(kReflectanceB)};

    // Next-event estimation (connectToLight with sampleTriangle, sampleSphere or the
    // environment, and the diffuse lobe). A batch with several kinds of light computes each
    // kind's sample and keeps each lane's.
    const batch u1 = get(kULight1), u2 = get(kULight2);
    const batch lightKind = get(kLightKind);
    const lanes triangleLit = lightKind == batch(float(kTrianglePacketLight));
    const lanes sphereLit = lightKind == batch(float(kSpherePacketLight));
    const lanes environmentLit = lightKind == batch(float(kEnvironmentPacketLight));
    LanePacketLight sampled{zero, zero, lanes(false), batch(0.0f)};
    if (xsimd::any(triangleLit)) triangleLightPoints(lights, light, u1, u2, sampled);
    if (xsimd::any(sphereLit)) {
      LanePacketLight sphere;
      sphereLightPoints(lights, light, position, u1, u2, sphere);
      sampled.point = select(sphereLit, sphere.point, sampled.point);
      sampled.normal = select(sphereLit, sphere.normal, sampled.normal);
      sampled.cone = sphere.cone & sphereLit;
      sampled.coneDensity = sphere.coneDensity;
    }
    V3 radiance = gather3(lights.radianceR, lights.radianceG, lights.radianceB, light);
    const V3 toLight = sampled.point - position;
    const batch dist2 = dot(toLight, toLight);
    V3 lightDir = toLight / xsimd::sqrt(dist2);
    batch cosLight = -dot(sampled.normal, lightDir);
    // Solid-angle density, and the light point's density per unit area (LightSample::pdfLight).
    const batch pdfArea = gather(lights.pdfArea, light);
    batch lightPdf = xsimd::select(sampled.cone, sampled.coneDensity, pdfArea * dist2 / cosLight);
    batch lightPdfArea = xsimd::select(sampled.cone, lightPdf * cosLight / dist2, pdfArea);
    lanes reaches = (dist2 > batch(0.0f)) & (cosLight > batch(0.0f));
    V3 lightPoint = sampled.point, lightNormal = sampled.normal;
    if (xsimd::any(environmentLit)) {
      // A direction, no point: the recorded light vertex stands far along it (as
      // stageShadePath's environmentPoint), facing back; the density is a solid angle's.
      const LaneEnvironmentSample sky = environmentLightDirections(map, mapTables, lights, light, u1, u2);
      lightDir = select(environmentLit, sky.direction, lightDir);
      radiance = select(environmentLit, sky.radiance, radiance);
      lightPdf = xsimd::select(environmentLit, gather(lights.probability, light) * sky.pdf, lightPdf);
      lightPdfArea = xsimd::select(environmentLit, lightPdf, lightPdfArea);
      reaches = (environmentLit & sky.ok) | (~environmentLit & reaches);
      lightPoint = select(environmentLit, position + sky.direction * 1e6f, lightPoint);
      lightNormal = select(environmentLit, -sky.direction, lightNormal);
    }
    const batch cosOut = dot(lightDir, frame.n) * flip;
    const V3 f = reflectance * (cosOut * kInvPi);
    const batch bsdfPdf = cosOut * kInvPi;
    const lanes connects = seen & reaches & (cosOut > batch(0.0f)) & ~isBlack(f);
    const batch a2 = lightPdf * lightPdf, p2b = bsdfPdf * bsdfPdf;
    const batch mis = xsimd::select(a2 + p2b > batch(0.0f), a2 / (a2 + p2b), batch(0.0f));
    const V3 contribution = f * radiance * (mis / lightPdf);
    putMask(kNeeOk, connects);
    put3(kNgx, ng);
    put3(kNsx, frame.n);
    put(kNeeMis, mis);
    put(kNeeBsdfPdf, bsdfPdf);
    put3(kLightPx, lightPoint);
    put3(kLightNx, lightNormal);
    put(kNeeLightPdf, lightPdfArea);
    put3(kNeeR, throughput * contribution);
    LaneShadowSegment shadow = shadowSegment(position, ng, sampled.point, sampled.normal);
    if (xsimd::any(environmentLit)) {  // towards infinity (connectToLight)
      shadow.origin = select(environmentLit, offsetOrigin(position, ng, lightDir), shadow.origin);
      shadow.direction = select(environmentLit, lightDir, shadow.direction);
      shadow.tfar = xsimd::select(environmentLit, batch(std::numeric_limits<float>::infinity()), shadow.tfar);
    }
    put3(kShadowOx, shadow.origin);
    put3(kShadowDx, shadow.direction);
    put(kShadowTfar, shadow.tfar);

    // The cosine-weighted bounce (bsdfSample's diffuse lobe).
    const V3 wo = cosineHemisphereLanes(get(kUBsdf1), get(kUBsdf2));
    const batch pdf = wo.z * kInvPi;
    const V3 weight = (reflectance * (wo.z * kInvPi)) / pdf;
    const lanes bounces = seen & (wo.z > batch(0.0f)) & (pdf > batch(0.0f)) & ~isBlack(weight);
    const V3 woWorld = frame.toWorld({wo.x, wo.y, wo.z * flip});
    putMask(kBounceOk, bounces);
    put3(kNextR, throughput * weight);
    put(kBsdfPdf, pdf);
    put3(kPx, position);
    put3(kRayOx, offsetOrigin(position, ng, woWorld));
    put3(kRayDx, woWorld);
  }

  auto get3 = [&](int first, size_t j) { return Vec3(out_[first][j], out_[first + 1][j], out_[first + 2][j]); };
  const bool recording = history.vertices != nullptr;
  for (size_t j = 0; j < count_; ++j) {
    const size_t k = size_t(slot_[j]);
    const uint32_t id = slots.path[k];
    const size_t vertex = history.base + k;
    slots.alive[k] = 0;
    if (recording) {  // the hit, as setSurfaceVertex writes it (a diffuse, non-emitting triangle)
      const uint32_t tri = uint32_t(triangle_[j]);
      const uint32_t i0 = mesh.v0[tri], i1 = mesh.v1[tri], i2 = mesh.v2[tri];
      const float b1 = hits.u[k], b2 = hits.v[k], b0 = 1 - b1 - b2;
      VertexQueue::Row v;  // the whole row: pdfForward 0 and the parent link are written too
      v.p = get3(kPx, j);
      v.ns = get3(kNsx, j);
      v.ng = get3(kNgx, j);
      v.material = mesh.material[tri];
      v.u = mesh.u[i0] * b0 + mesh.u[i1] * b1 + mesh.u[i2] * b2;
      v.v = mesh.v[i0] * b0 + mesh.v[i1] * b1 + mesh.v[i2] * b2;
      v.kind = kNonSpecularVertex;
      v.parent = paths.lastVertex[id];
      history.vertices->setRow(vertex, v);
      paths.lastVertex[id] = int32_t(vertex);
      slots.emitWeight[k] = slots.neeWeight[k] = 0;
      slots.pLengthHere[k] = paths.pLength[id];
    }
    if (out_[kNeeOk][j] != 0 && int(paths.depth[id]) + 1 >= ctx.minSegments) {
      slots.neeSet(k, get3(kNeeR, j));
      setRay(shadowRays, k, get3(kShadowOx, j), get3(kShadowDx, j), 0.0f, out_[kShadowTfar][j]);
      if (recording) {
        slots.neeWeight[k] = out_[kNeeMis][j];
        slots.neeBsdfPdf[k] = out_[kNeeBsdfPdf][j];
        slots.neeLightPdf[k] = out_[kNeeLightPdf][j];
        slots.neeLightKind[k] = in_[kLightKind][j] == float(kEnvironmentPacketLight) ? kEnvironmentVertex : kLightVertex;
        slots.neeLightEmitter[k] = lights.emitter[size_t(light_[j])];
        slots.neeLightSet(k, get3(kLightPx, j));
        slots.neeLightNSet(k, get3(kLightNx, j));
      }
    } else {
      slots.neeSet(k, Color(0.0f));
      disableRay(shadowRays, k);
    }
    if (out_[kBounceOk][j] == 0) continue;
    if (recording) {
      history.vertices->pdfForward[vertex] = out_[kBsdfPdf][j];
      history.vertices->kind[vertex] = kNonSpecularVertex;
    }
    Color next = get3(kNextR, j);
    const uint32_t depth = paths.depth[id];
    if (int(depth) >= ctx.rrDepth) {  // Russian roulette, as in stageShadePath (reflection: eta 1)
      const float q = russianRouletteSurvival(next, paths.etaSquared[id]);
      if (!(roulette_[j] < q)) continue;
      next = next / q;
      paths.pLength[id] *= q;
    }
    paths.throughputSet(id, next);
    paths.prevPdf[id] = out_[kBsdfPdf][j];
    paths.prevSet(id, get3(kPx, j));
    paths.depth[id] = depth + 1;
    setRay(rays, k, get3(kRayOx, j), get3(kRayDx, j), 0.0f, std::numeric_limits<float>::infinity());
    slots.alive[k] = 1;
  }
  count_ = 0;
}

}  // namespace erpt
