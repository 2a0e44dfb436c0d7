// The diffuse walk kernel (bdpt_walk_diffuse.h): gather, vector body, scatter. Every formula
// mirrors the scalar code it replaces for these vertices: triangleSurfaceAt, areaDensity,
// Frame, the diffuse lobe of bsdfSample, bsdfAdjointWeight and bsdfPdf, offsetOrigin, and the
// bookkeeping and roulette of stageBdptExtend.
#include "stages/bdpt_walk_diffuse.h"

#include <limits>

#include "core/rng.h"
#include "kernels/lane_gather.h"
#include "kernels/lane_vec3.h"
#include "kernels/surface_lanes.h"
#include "tracer/tracer.h"

namespace erpt {

namespace {

using namespace lanes3;
constexpr size_t kLanes = batch::size;
static_assert(BdptDiffuseWalkPacket::kCapacity % kLanes == 0, "a packet is whole batches");

// areaDensity of bdpt_vertex.h for a density at `from` of the direction to `to`, neither at
// infinity, with `toNormal` the normal at `to`.
batch areaDensityLanes(const batch& pdf, const V3& from, const V3& to, const V3& toNormal) {
  const V3 d = to - from;
  const batch d2 = dot(d, d);
  return xsimd::select(d2 > batch(0.0f), pdf * xsimd::abs(dot(toNormal, d)) / (d2 * xsimd::sqrt(d2)), batch(0.0f));
}

}  // namespace

bool BdptDiffuseWalkPacket::add(const BdptContext& ctx, BdptSide side, const BdptSubpaths& paths,
                                const BdptWalkQueue& walks, const HitQueue& hits, size_t k) {
  const uint32_t geom = hits.geomID[k];
  if (geom == kNoHit || geom == kRefusedRay) return false;
  const Scene& scene = ctx.stage.scene;
  const TriangleSoup& mesh = scene.mesh;
  const uint32_t tri = hits.primID[k];
  if (tri >= mesh.triangleCount()) return false;
  const Material& m = scene.materials[size_t(mesh.material[tri])];
  if (m.kind != BsdfKind::Diffuse || m.reflectance.texture >= 0 || m.adjustsShadingFrame()) return false;
  const uint32_t i = walks.sample[k], depth = walks.depth[k];
  const int32_t previous = walks.vertex[k];

  const size_t j = count_++;
  slot_[j] = int32_t(k);
  triangle_[j] = int32_t(tri);
  previous_[j] = previous;
  in_[kSmooth][j] = mesh.smooth[tri] != 0 ? 1.0f : 0.0f;
  in_[kTwoSided][j] = m.twoSided ? 1.0f : 0.0f;
  in_[kReflectanceR][j] = m.reflectance.value.x;
  in_[kReflectanceG][j] = m.reflectance.value.y;
  in_[kReflectanceB][j] = m.reflectance.value.z;
  in_[kPrevAtInfinity][j] = paths.vertices.kind[size_t(previous)] == kEnvironmentVertex ? 1.0f : 0.0f;
  // The bounce's numbers, drawn where the scalar walk samples a bounce. Replaying a chain's
  // primary samples, reading a number keeps it in the chain's state, so the lobe's number is
  // read too, as bsdfSample's caller reads it. Two rare cases still read more than the scalar
  // walk: a light walk arriving at a grazing 0 cosine (which ends before its bounce), and the
  // roulette's number of a bounce that fails (the back of a one-sided surface). Both leave the
  // path unchanged, and a number the path does not use is uniform under the chain's target
  // whether it is kept or drawn afresh (kernels/primary_samples.h): the chain stays exact, and
  // only differs from the scalar walk's in which such numbers it keeps.
  bounces_[j] = bdptWalkContinues(ctx, side, paths, i, depth);
  if (bounces_[j]) {
    const uint64_t key = side == BdptSide::Light ? lightSubpathStream(ctx.stage, paths.pixel[i], paths.sample[i])
                                                 : sampleStream(ctx.stage, paths.pixel[i], paths.sample[i]);
    if (ctx.stage.replay) drawFloat(ctx.stage, key, bounceDim(depth, kLobe));
    in_[kUBsdf1][j] = drawFloat(ctx.stage, key, bounceDim(depth, kBsdf1));
    in_[kUBsdf2][j] = drawFloat(ctx.stage, key, bounceDim(depth, kBsdf2));
    roulette_[j] = int(depth) >= ctx.stage.rrDepth ? drawDouble(ctx.stage, key, bounceDim(depth, kRoulette)) : 0.0;
  }
  return true;
}

void BdptDiffuseWalkPacket::extend(const BdptContext& ctx, BdptSide side, BdptSubpaths& paths, BdptWalkQueue& walks,
                                   RayQueue& rays, const HitQueue& hits, size_t base, std::vector<uint8_t>& alive) {
  if (count_ == 0) return;
  // Rows past count_, up to a whole batch, gather row 0's entries: computed, never stored.
  for (size_t j = count_; j % kLanes != 0; ++j) slot_[j] = slot_[0], triangle_[j] = triangle_[0], previous_[j] = previous_[0];
  const bool fromLight = side == BdptSide::Light;
  const Scene& scene = ctx.stage.scene;
  const TriangleSoup& mesh = scene.mesh;
  BdptVertexQueue& vertices = paths.vertices;
  for (size_t b = 0; b < count_; b += kLanes) {
    auto get = [&](int c) { return batch::load_aligned(&in_[c][b]); };
    auto put = [&](int c, const batch& v) { v.store_aligned(&out_[c][b]); };
    auto put3 = [&](int first, const V3& v) { put(first, v.x), put(first + 1, v.y), put(first + 2, v.z); };
    auto gather = [](const auto& column, const indices& at) { return gatherLanes(column.data(), at); };
    auto gather3 = [&](const auto& x, const auto& y, const auto& z, const indices& at) {
      return V3{gather(x, at), gather(y, at), gather(z, at)};
    };
    const indices slot = indices::load_aligned(&slot_[b]), triangle = indices::load_aligned(&triangle_[b]);
    const indices previous = indices::load_aligned(&previous_[b]);

    const LaneTriangleHit hit =
        triangleHitLanes(mesh, triangle, gather(hits.u, slot), gather(hits.v, slot), get(kSmooth) != batch(0.0f));
    const V3 position = hit.position, ng = hit.ng;
    const LaneFrame frame(hit.shading);
    V3 dir = gather3(rays.dirX, rays.dirY, rays.dirZ, slot);
    dir = dir / xsimd::sqrt(dot(dir, dir));
    const V3 prevP = gather3(vertices.pX, vertices.pY, vertices.pZ, previous);
    const V3 prevNg = gather3(vertices.ngX, vertices.ngY, vertices.ngZ, previous);
    const mask prevAtInfinity = get(kPrevAtInfinity) != batch(0.0f);
    const batch pdfNext = gather(walks.pdfNext, slot);
    put(kPdfForward, xsimd::select(prevAtInfinity, pdfNext * xsimd::abs(dot(ng, prevNg)),
                                   areaDensityLanes(pdfNext, prevP, position, ng)));
    put(kCosIn, xsimd::abs(dot(ng, dir)));
    put3(kPx, position);
    put3(kNgx, ng);
    put3(kNsx, frame.n);

    // The cosine-weighted bounce on the side the ray arrived from (bsdfSample's diffuse lobe).
    const V3 wi = frame.toLocal(-dir);
    const batch flip = xsimd::select(wi.z > batch(0.0f), batch(1.0f),
                                     xsimd::select((get(kTwoSided) != batch(0.0f)) & (wi.z < batch(0.0f)), batch(-1.0f),
                                                   batch(0.0f)));
    const V3 reflectance{get(kReflectanceR), get(kReflectanceG), get(kReflectanceB)};
    const V3 lobe = cosineHemisphereLanes(get(kUBsdf1), get(kUBsdf2));
    const batch pdf = lobe.z * kInvPi;
    const V3 woLocal{lobe.x, lobe.y, lobe.z * flip};
    const V3 wo = frame.toWorld(woLocal);
    const batch wiAbs = xsimd::abs(wi.z), woAbs = xsimd::abs(woLocal.z);
    V3 weight = (reflectance * (lobe.z * kInvPi)) / pdf;
    if (fromLight) {  // bsdfAdjointWeight, times Veach's shading-normal factor
      const batch cosOut = xsimd::abs(dot(ng, wo));
      weight = (reflectance * (wiAbs * kInvPi)) * (woAbs / (wiAbs * pdf)) * (cosOut * wiAbs / woAbs);
    }
    const mask bounces = (flip != batch(0.0f)) & (lobe.z > batch(0.0f)) & (pdf > batch(0.0f)) & (woLocal.z != batch(0.0f)) &
                         ~isBlack(weight);
    put(kBounceOk, xsimd::select(bounces, batch(1.0f), batch(0.0f)));
    put3(kWeightR, weight);
    put(kPdfNext, pdf);
    // The previous vertex as sampled from here: the lobe's density of the way back.
    const batch reverse = wiAbs * kInvPi;
    put(kPdfReverse, xsimd::select(prevAtInfinity, reverse, areaDensityLanes(reverse, position, prevP, prevNg)));
    put3(kRayOx, offsetOrigin(position, ng, wo));
    put3(kRayDx, wo);
  }

  // The scalar walk's bookkeeping, slot by slot.
  auto get3 = [&](int first, size_t j) { return Vec3(out_[first][j], out_[first + 1][j], out_[first + 2][j]); };
  for (size_t j = 0; j < count_; ++j) {
    const size_t k = size_t(slot_[j]);
    alive[k] = 0;
    const uint32_t i = walks.sample[k];
    const uint32_t depth = walks.depth[k];
    const int32_t prevIndex = previous_[j];
    const uint32_t tri = uint32_t(triangle_[j]);
    const size_t v = base + k;
    const float cosIn = out_[kCosIn][j];
    BdptVertex x;  // surfaceVertex's fields for a diffuse triangle
    x.p = get3(kPx, j);
    x.ns = get3(kNsx, j);
    x.ng = get3(kNgx, j);
    x.material = mesh.material[tri];
    const uint32_t i0 = mesh.v0[tri], i1 = mesh.v1[tri], i2 = mesh.v2[tri];
    const float b1 = hits.u[k], b2 = hits.v[k], b0 = 1 - b1 - b2;
    x.u = mesh.u[i0] * b0 + mesh.u[i1] * b1 + mesh.u[i2] * b2;
    x.v = mesh.v[i0] * b0 + mesh.v[i1] * b1 + mesh.v[i2] * b2;
    x.kind = kNonSpecularVertex;
    x.emitter = mesh.emitter[tri];
    x.primitive = tri;
    x.parent = prevIndex;
    x.pdfForward = out_[kPdfForward][j];
    x.pdfReverse = 0;
    if (fromLight) {
      if (!(cosIn > 0)) continue;
      x.beta = walks.betaAt(k) / cosIn;
      if (depth == 1) paths.lightNextEvent[i] = nextEventDensity(ctx.stage.lights, vertices.row(size_t(prevIndex)), x.p);
    } else {
      x.beta = walks.betaAt(k);
    }
    (fromLight ? paths.lightEnd : paths.cameraEnd)[i] = int32_t(v);
    vertices.setRow(v, x);
    if (!bounces_[j] || out_[kBounceOk][j] == 0) continue;
    if (vertices.kind[size_t(prevIndex)] != kEyeVertex) vertices.pdfReverse[size_t(prevIndex)] = out_[kPdfReverse][j];
    const Color weight = get3(kWeightR, j);
    Color beta = x.beta * weight;
    Color scatter = walks.scatterAt(k) * (fromLight ? weight / cosIn : weight);
    if (int(depth) >= ctx.stage.rrDepth) {  // a reflection: eta 1, etaSquared unchanged
      const float q = russianRouletteSurvival(scatter, walks.etaSquared[k]);
      if (!(roulette_[j] < q)) continue;
      beta = beta / q;
      scatter = scatter / q;
    }
    walks.betaSet(k, beta);
    walks.scatterSet(k, scatter);
    walks.pdfNext[k] = out_[kPdfNext][j];
    walks.vertex[k] = int32_t(v);
    walks.depth[k] = depth + 1;
    setRay(rays, k, get3(kRayOx, j), get3(kRayDx, j), 0.0f, std::numeric_limits<float>::infinity());
    alive[k] = 1;
  }
  count_ = 0;
}

}  // namespace erpt
