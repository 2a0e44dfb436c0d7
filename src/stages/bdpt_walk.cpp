// BDPT's walks: the light and camera subpaths, one bounce per call over the live walks.
//
// What a vertex carries (docs/bdpt.md derives it). The path contribution is
//   f(x) = W(x0, x1) prod_{i=1}^{k-1} F_i prod_{j=1}^{k} |cos_g(x_j -> x_{j-1})| / d_j^2 Le(x_k -> x_{k-1})
// with F_i = bsdfEval at x_i (camera side first, so it holds the shading cosine towards the
// light side): the path tracer's measure. A camera vertex's beta is the path tracer's
// throughput. A light vertex z_i's beta is the light part of f over its density, which ends in
// 1 / |cos_g(z_i -> z_{i-1})|: the connection's F at z_i (with its shading cosine towards
// z_{i-1}) completes it into Veach's adjoint shading-normal factor. The light vertex's own
// beta is 1 / pdfPosition (its emission is evaluated at the connection). A bounce's weight is
// bsdfAdjointWeight's: for a Dirac lobe, the lobe's own weight without radiance's eta^2
// (docs/bdpt.md, "Light subpaths through Dirac lobes").
#include <limits>

#include "core/rng.h"
#include "kernels/bdpt_vertex.h"
#include "kernels/surface_vertex.h"
#include "stages/bdpt_stages.h"
#include "stages/bdpt_walk_diffuse.h"
#include "tracer/tracer.h"

namespace erpt {

namespace {
BdptVertex surfaceVertex(const Scene& scene, const SurfacePoint& sp) {
  BdptVertex v;
  setSurfaceVertex(v, sp, scene.materials[size_t(sp.material)]);
  v.kind = kNonSpecularVertex;  // until a Dirac lobe is taken here
  v.primitive = sp.primitive;
  return v;
}
}  // namespace

uint64_t lightSubpathKey(uint64_t seed, uint32_t pixel, uint32_t sample) {
  return sampleKey(mix64(seed ^ 0x4c6967687450617eull), pixel, sample);
}

uint64_t lightSubpathStream(const StageContext& ctx, uint32_t pixel, uint32_t sample) {
  return ctx.replay ? (uint64_t(sample) | kLightSubpathStream) : lightSubpathKey(ctx.seed, pixel, sample);
}

void BdptSubpaths::resizeSamples(size_t n) {
  for (auto* v : {&pixel, &sample}) v->resize(n);
  for (auto* v : {&filmX, &filmY, &lightNextEvent}) v->assign(n, 0.0f);
  lightEnd.assign(n, -1);
  cameraEnd.assign(n, -1);
  invalid.assign(n, 0);
  strategyS.clear();
  strategyT.clear();
  used = 0;
}

void BdptSubpaths::reserveVertices(size_t more) {
  if (used + more <= vertices.size()) return;
  vertices.resize(std::max(used + more, vertices.size() * 3 / 2));
}

void stageBdptStartLight(const BdptContext& ctx, BdptSubpaths& paths, BdptWalkQueue& walks, RayQueue& rays,
                         size_t base, std::vector<uint8_t>& alive, IndexRange range) {
  const LightSampler& lights = ctx.stage.lights;
  for (size_t i = range.begin; i < range.end; ++i) {
    walks.sample[i] = uint32_t(i);
    alive[i] = 0;
    disableRay(rays, i);
    paths.lightEnd[i] = -1;
    const uint64_t key = lightSubpathStream(ctx.stage, paths.pixel[i], paths.sample[i]);
    const StageContext& c = ctx.stage;
    EmissionSample es;
    const int cap = bdptVertexCap(paths, BdptSide::Light, i);
    if (ctx.stage.maxDepth == 0 || cap == 0 ||
        !lights.sampleEmission(drawDouble(c, key, kDimEmitPick), drawFloat(c, key, kDimEmit1),
                               drawFloat(c, key, kDimEmit1 + 1), drawFloat(c, key, kDimEmit1 + 2),
                               drawFloat(c, key, kDimEmit1 + 3), es))
      continue;
    BdptVertex z;
    z.kind = es.infinite ? kEnvironmentVertex : kLightVertex;
    z.p = es.origin;
    z.ng = z.ns = es.infinite ? -es.direction : (es.deltaPosition ? Vec3(0.0f) : es.normal);
    z.emitter = es.emitter;
    z.primitive = es.primitive;
    z.beta = Color(1.0f / es.pdfPosition);
    z.pdfForward = es.pdfPosition;
    z.pdfReverse = 0;
    z.parent = -1;
    const size_t v = base + i;
    paths.vertices.setRow(v, z);
    paths.lightEnd[i] = int32_t(v);
    walks.betaSet(i, es.value * (es.cosAtLight / (es.pdfPosition * es.pdfDirection)));
    walks.scatterSet(i, Color(1.0f));
    walks.etaSquared[i] = 1;
    walks.pdfNext[i] = es.pdfDirection;
    walks.vertex[i] = int32_t(v);
    walks.depth[i] = 1;
    // A second light vertex needs paths of two segments or more.
    if ((ctx.stage.maxDepth >= 0 && ctx.stage.maxDepth < 2) || (cap >= 0 && cap < 2)) continue;
    const bool onSurface = !es.infinite && !es.deltaPosition;  // leave the emitting surface
    setRay(rays, i, onSurface ? offsetOrigin(es.origin, es.normal, es.direction) : es.origin, es.direction, 0.0f,
           std::numeric_limits<float>::infinity());
    alive[i] = 1;
  }
}

void stageBdptStartCamera(const BdptContext& ctx, BdptSubpaths& paths, BdptWalkQueue& walks, RayQueue& rays,
                          size_t base, std::vector<uint8_t>& alive, IndexRange range) {
  stageGenerateCameraRays(ctx.stage, paths.pixel.data(), paths.sample.data(), rays, range, paths.filmX.data(),
                          paths.filmY.data());
  const Camera& camera = ctx.stage.camera;
  for (size_t i = range.begin; i < range.end; ++i) {
    walks.sample[i] = uint32_t(i);
    BdptVertex y;
    y.kind = kEyeVertex;
    y.p = rays.orgAt(i);
    y.ng = y.ns = camera.forward();
    y.beta = Color(1.0f);
    y.pdfForward = 1;  // the lens point: the same for every strategy (t >= 1), so it cancels
    y.pdfReverse = 0;
    y.parent = -1;
    const size_t v = base + i;
    paths.vertices.setRow(v, y);
    paths.cameraEnd[i] = int32_t(v);
    walks.betaSet(i, Color(1.0f));
    walks.scatterSet(i, Color(1.0f));
    walks.etaSquared[i] = 1;
    walks.pdfNext[i] = cameraDirectionDensity(camera, ctx.stage.width, ctx.height, normalize(rays.dirAt(i)));
    walks.vertex[i] = int32_t(v);
    walks.depth[i] = 1;
    const int cap = bdptVertexCap(paths, BdptSide::Camera, i);
    alive[i] = cap < 0 || cap >= 2;
  }
}

void stageBdptExtend(const BdptContext& ctx, BdptSide side, BdptSubpaths& paths, BdptWalkQueue& walks, RayQueue& rays,
                     const HitQueue& hits, size_t base, std::vector<uint8_t>& alive, IndexRange range) {
  const Scene& scene = ctx.stage.scene;
  const bool fromLight = side == BdptSide::Light;
  BdptVertexQueue& vertices = paths.vertices;
  // Plain diffuse triangles go to the vector kernel, a packet at a time; the rest run the body below.
  BdptDiffuseWalkPacket diffuse;
  const bool vector = ctx.stage.vectorShading;
  for (size_t k = range.begin; k < range.end; ++k) {
    if (vector && diffuse.add(ctx, side, paths, walks, hits, k)) {
      if (diffuse.full()) diffuse.extend(ctx, side, paths, walks, rays, hits, base, alive);
      continue;
    }
    alive[k] = 0;
    const uint32_t i = walks.sample[k];
    const uint32_t depth = walks.depth[k];  // segments so far, the ray just traced included
    const int32_t prevIndex = walks.vertex[k];
    const BdptVertex prev = vertices.row(size_t(prevIndex));
    const Vec3 dir = normalize(rays.dirAt(k));
    const size_t v = base + k;
    if (hits.geomID[k] == kRefusedRay) {
      paths.invalid[i] = 1;
      continue;
    }
    if (hits.geomID[k] == kNoHit) {
      const Emitter* env = scene.environment();
      if (fromLight || !env) continue;
      BdptVertex y;  // the environment, seen along the escaping ray
      y.kind = kEnvironmentVertex;
      y.ng = y.ns = dir;
      y.p = prev.p + dir * 1e6f;
      y.emitter = int32_t(env - scene.emitters.data());
      y.beta = walks.betaAt(k);
      y.pdfForward = walks.pdfNext[k];
      y.pdfReverse = 0;
      y.parent = prevIndex;
      vertices.setRow(v, y);
      paths.cameraEnd[i] = int32_t(v);
      continue;
    }
    const SurfacePoint sp = surfaceAt(scene, hits.primID[k], hits.u[k], hits.v[k]);
    BdptVertex x = surfaceVertex(scene, sp);
    x.parent = prevIndex;
    x.pdfForward = areaDensity(walks.pdfNext[k], prev, x);
    x.pdfReverse = 0;
    const float cosIn = std::abs(dot(x.ng, dir));
    if (fromLight) {
      if (!(cosIn > 0)) continue;
      x.beta = walks.betaAt(k) / cosIn;
      if (depth == 1) paths.lightNextEvent[i] = nextEventDensity(ctx.stage.lights, prev, x.p);
    } else {
      x.beta = walks.betaAt(k);
    }
    (fromLight ? paths.lightEnd : paths.cameraEnd)[i] = int32_t(v);
    vertices.setRow(v, x);

    if (!bdptWalkContinues(ctx, side, paths, i, depth)) continue;
    const uint64_t key = fromLight ? lightSubpathStream(ctx.stage, paths.pixel[i], paths.sample[i])
                                   : sampleStream(ctx.stage, paths.pixel[i], paths.sample[i]);
    const VertexBsdf bsdf = vertexBsdf(scene, x);
    const Vec3 back = -dir;  // towards the previous vertex
    const Vec3 wiLocal = bsdf.frame.toLocal(back);
    BsdfSample bs;
    if (!bsdfSample(*bsdf.material, bsdf.colors, wiLocal, drawFloat(ctx.stage, key, bounceDim(depth, kLobe)),
                    drawFloat(ctx.stage, key, bounceDim(depth, kBsdf1)), drawFloat(ctx.stage, key, bounceDim(depth, kBsdf2)),
                    bs) ||
        !(bs.pdf > 0) || bs.wo.z == 0)
      continue;
    const Vec3 wo = bsdf.frame.toWorld(bs.wo);
    const float cosOut = std::abs(dot(x.ng, wo));
    Color weight = bs.weight;
    if (fromLight)  // the adjoint with Veach's shading-normal factor; times x.beta, which holds 1 / cosIn
      weight = bsdfAdjointWeight(*bsdf.material, bsdf.colors, wiLocal, bs) *
               (cosOut * std::abs(wiLocal.z) / std::abs(bs.wo.z));
    if (isBlack(weight)) continue;
    // The previous vertex as sampled from here (the camera's is never needed: t >= 1).
    if (prev.kind != kEyeVertex) {
      const float reverse = bs.delta ? bs.pdf : bsdf.pdf(wo, back);
      vertices.pdfReverse[size_t(prevIndex)] = areaDensity(reverse, x, prev);
    }
    vertices.kind[v] = bs.delta ? kSpecularVertex : kNonSpecularVertex;
    Color beta = x.beta * weight;
    Color scatter = walks.scatterAt(k) * (fromLight ? weight / cosIn : weight);  // the bounce's albedo-like weight
    walks.etaSquared[k] *= bs.eta * bs.eta;
    if (int(depth) >= ctx.stage.rrDepth) {
      const float q = russianRouletteSurvival(scatter, walks.etaSquared[k]);
      if (!(drawDouble(ctx.stage, key, bounceDim(depth, kRoulette)) < q)) continue;
      beta = beta / q;
      scatter = scatter / q;
    }
    walks.betaSet(k, beta);
    walks.scatterSet(k, scatter);
    walks.pdfNext[k] = bs.pdf;
    walks.vertex[k] = int32_t(v);
    walks.depth[k] = depth + 1;
    setRay(rays, k, offsetOrigin(x.p, x.ng, wo), wo, 0.0f, std::numeric_limits<float>::infinity());
    alive[k] = 1;
  }
  diffuse.extend(ctx, side, paths, walks, rays, hits, base, alive);
}

}  // namespace erpt
