// BDPT's connections: every strategy (s, t) of a sample, with its MIS weight
// (kernels/bdpt_mis.h). s = 0: emission the camera subpath hit; s = 1: next-event estimation
// from a camera vertex; s >= 2, t >= 2: a light vertex joined to a camera vertex; t = 1: a
// light vertex joined to the lens, splatted where it lands on the film (light tracing).
#include <algorithm>
#include <limits>
#include <new>
#include <type_traits>

#include "core/rng.h"
#include "kernels/bdpt_mis.h"
#include "kernels/bdpt_vertex.h"
#include "stages/bdpt_stages.h"
#include "tracer/tracer.h"

namespace erpt {

static_assert(std::is_trivially_destructible_v<VertexBsdf>, "stageBdptConnect constructs VertexBsdf over old ones");

namespace {

// The subpath ending at vertex `last`, in walk order (its first vertex first).
void gatherSubpath(const BdptVertexQueue& vertices, int32_t last, std::vector<BdptVertex>& out,
                   std::vector<int32_t>& index) {
  out.clear();
  index.clear();
  for (int32_t v = last; v >= 0; v = vertices.parent[size_t(v)]) {
    out.push_back(vertices.row(size_t(v)));
    index.push_back(v);
  }
  std::reverse(out.begin(), out.end());
  std::reverse(index.begin(), index.end());
}

bool hittableLight(const Scene& scene, const BdptVertex& light) {
  const EmitterKind kind = scene.emitters[size_t(light.emitter)].kind;
  return kind == EmitterKind::Area || kind == EmitterKind::Constant;
}
bool areaLight(const Scene& scene, const BdptVertex& light) {
  return scene.emitters[size_t(light.emitter)].kind == EmitterKind::Area;
}

// The densities of one path x_0 .. x_k made by strategy (s, t), for its MIS weight: the
// subpaths' own (camera[0 .. t), light[0 .. s), light[0] the light vertex, x_{t+m} =
// light[s-1-m]), with the four that the connection changes passed in: x_t and x_{t+1} sampled
// from the camera side, x_{t-1} and x_{t-2} from the light side.
struct MisBuilder {
  BdptConnectScratch& scratch;
  BdptMisPath path;
  void build(const BdptVertex* camera, int t, const BdptVertex* light, int s, float cameraT, float cameraT1,
             float lightT1, float lightT2) {
    const int k = s + t - 1;
    if (scratch.cameraDensity.size() <= size_t(k)) {  // grown only: every entry up to k is written below
      scratch.cameraDensity.resize(size_t(k) + 1);
      scratch.lightDensity.resize(size_t(k) + 1);
      scratch.specular.resize(size_t(k) + 1);
    }
    float* pc = scratch.cameraDensity.data();
    float* pl = scratch.lightDensity.data();
    uint8_t* specular = scratch.specular.data();
    for (int i = 0; i < t; ++i) {
      pc[i] = camera[i].pdfForward;
      pl[i] = camera[i].pdfReverse;
      specular[i] = camera[i].kind == kSpecularVertex;
    }
    for (int i = t; i <= k; ++i) {
      const BdptVertex& z = light[k - i];
      pl[i] = z.pdfForward;
      pc[i] = z.pdfReverse;
      specular[i] = z.kind == kSpecularVertex;
    }
    if (t <= k) pc[t] = cameraT;
    if (t + 1 <= k) pc[t + 1] = cameraT1;
    if (t >= 1) pl[t - 1] = lightT1;
    if (t >= 2) pl[t - 2] = lightT2;
    pl[0] = 0;  // the camera is never hit (t >= 1)
    if (t >= 1) specular[t - 1] = 0;
    if (t <= k) specular[t] = 0;
    path.k = k;
    path.cameraDensity = pc;
    path.lightDensity = pl;
    path.specular = specular;
  }
};

// The BSDFs of a subpath's vertices: all of them (`only` < 0), or vertex only - 1's alone (none
// for only = 0); and for each vertex j >= 1 with one, the direction back to vertex j - 1 in its
// frame.
void prepareSubpath(const Scene& scene, const std::vector<BdptVertex>& subpath, int only, std::vector<VertexBsdf>& bsdf,
                    std::vector<Vec3>& backLocal) {
  // Grown, never shrunk: a resize to each sample's lengths constructed the rows again.
  if (bsdf.size() < subpath.size()) {
    bsdf.resize(subpath.size());
    backLocal.resize(subpath.size());
  }
  for (size_t j = 0; j < subpath.size(); ++j) {
    if (only >= 0 && int(j) != only - 1) {
      bsdf[j].material = nullptr;
      continue;
    }
    // Constructed in place (VertexBsdf is trivially destructible): an assignment copied each
    // vertex's BSDF, colours and all, once more.
    new (&bsdf[j]) VertexBsdf(vertexBsdf(scene, subpath[j]));
    if (j >= 1 && bsdf[j].material) backLocal[j] = bsdf[j].frame.toLocal(directionTo(subpath[j], subpath[j - 1]));
  }
}

}  // namespace

void stageBdptConnect(const BdptContext& ctx, const BdptSubpaths& paths, BdptConnectScratch& scratch,
                      std::vector<Color>& radiance, BdptConnectionQueue& connections, RayQueue& rays, IndexRange range) {
  const Scene& scene = ctx.stage.scene;
  const LightSampler& lights = ctx.stage.lights;
  const Camera& camera = ctx.stage.camera;
  const int maxDepth = ctx.stage.maxDepth;
  const int width = ctx.stage.width, height = ctx.height;
  const float ppu = camera.pixelsPerPlaneUnit();
  int sampleS = -1, sampleT = -1;  // the one strategy of the sample being connected (mmlt), or -1: all
  auto keep = [&](int s, int t) {
    return (ctx.onlyS < 0 || s == ctx.onlyS) && (ctx.onlyT < 0 || t == ctx.onlyT) && (sampleS < 0 || s == sampleS) &&
           (sampleT < 0 || t == sampleT) &&
           (maxDepth < 0 || s + t - 1 <= maxDepth) && s + t - 1 >= ctx.stage.minSegments;
  };
  auto weight = [&](const MisBuilder& mis, int s) { return ctx.unweighted ? 1.0f : bdptMisWeight(mis.path, s); };
  // Appends a contribution of strategy (s, t) with its shadow ray from `from` to `to` (none for s = 0).
  // The queue grows ahead of the connections, by doubling and without zeroing (every column of
  // a connection is written), and is cut to `used` at the end: growing it by one row per
  // connection cost BDPT some 7% of its time in per-column resizes.
  size_t used = connections.size();
  auto addConnection = [&](uint32_t sample, int s, int t, Color value, float misWeight, int32_t cameraVertex,
                           int32_t lightVertex, const Vec3* from, Vec3 to, float fx, float fy) {
    const size_t n = used++;
    if (used > connections.size()) connections.resizeForOverwrite(std::max<size_t>(1024, 2 * connections.size()));
    if (n + 1 > rays.size()) {
      RayQueue bigger;
      prepareRays(bigger, std::max<size_t>(1024, rays.size() * 2));
      for (size_t r = 0; r < rays.size(); ++r) bigger.copyRow(r, rays, r);
      rays = std::move(bigger);
    }
    connections.sample[n] = sample;
    connections.valueSet(n, value);
    connections.misWeight[n] = misWeight;
    connections.s[n] = uint16_t(s);
    connections.t[n] = uint16_t(t);
    connections.cameraVertex[n] = cameraVertex;
    connections.lightVertex[n] = lightVertex;
    connections.toCamera[n] = t == 1;
    connections.filmX[n] = fx;
    connections.filmY[n] = fy;
    if (from) setRay(rays, n, *from, to - *from, 0.0f, 1 - 1e-4f);  // stops just short of the far vertex
    else disableRay(rays, n);
  };
  // Vertices that belong to no subpath (lens points, next-event light points): extra vertex e
  // is named -1 - e.
  auto addExtra = [&](const BdptVertex& v) {
    const size_t e = scratch.extraUsed++;
    if (scratch.extra.size() <= e) scratch.extra.resize(std::max<size_t>(256, 2 * e + 2));
    scratch.extra.setRow(e, v);
    return -1 - int32_t(e);
  };
  std::vector<BdptVertex>& light = scratch.light;
  std::vector<BdptVertex>& cam = scratch.camera;
  std::vector<VertexBsdf>& lightBsdf = scratch.lightBsdf;
  std::vector<VertexBsdf>& cameraBsdf = scratch.cameraBsdf;
  MisBuilder mis{scratch, {}};
  std::vector<int32_t>& lightIndex = scratch.lightIndex;
  std::vector<int32_t>& cameraIndex = scratch.cameraIndex;

  for (size_t i = range.begin; i < range.end; ++i) {
    sampleS = paths.strategyS.empty() ? -1 : paths.strategyS[i];
    sampleT = paths.strategyT.empty() ? -1 : paths.strategyT[i];
    if (paths.invalid[i]) {
      radiance[i] = Color(std::numeric_limits<float>::quiet_NaN());
      continue;
    }
    gatherSubpath(paths.vertices, paths.lightEnd[i], light, lightIndex);
    gatherSubpath(paths.vertices, paths.cameraEnd[i], cam, cameraIndex);
    // A sample of one strategy (s, t) reads only light[s - 1]'s BSDF and cam[t - 1]'s: the
    // others are left without a material, so that they read as not connectable (no strategy
    // that keep() refuses would reach them anyway).
    prepareSubpath(scene, light, sampleS, lightBsdf, scratch.lightBackLocal);
    prepareSubpath(scene, cam, sampleT, cameraBsdf, scratch.cameraBackLocal);
    const int nL = int(light.size()), nC = int(cam.size());
    const uint32_t sample = uint32_t(i);

    // s = 0: the camera subpath reached a light.
    for (int j = 1; j < nC; ++j) {
      const BdptVertex& y = cam[j];
      if (y.emitter < 0 || !keep(0, j + 1)) continue;
      const Vec3 back = directionTo(y, cam[j - 1]);
      const Color le = lightVertexEmission(scene, y, back);
      if (isBlack(le)) continue;
      float pdfPosition, pdfDirection;
      lights.emissionDensity(y.emitter, y.primitive, y.ng, back, pdfPosition, pdfDirection);
      mis.build(cam.data(), j + 1, nullptr, 0, 0, 0, 0, 0);
      float* pl = scratch.lightDensity.data();
      pl[j] = pdfPosition;
      pl[j - 1] = j - 1 >= 1 ? areaDensity(pdfDirection, y, cam[j - 1]) : 0.0f;
      scratch.specular[j] = 0;
      mis.path.nextEventDensity = nextEventDensity(lights, y, cam[j - 1].p);
      mis.path.lightHittable = true;
      mis.path.lightSeenByLightTracing = y.kind != kEnvironmentVertex;
      const float w = weight(mis, 0);
      addConnection(sample, 0, j + 1, y.beta * le * w, w, cameraIndex[size_t(j)], 0, nullptr, {}, 0, 0);
    }

    // s = 1: next-event estimation from camera vertex j (t = j + 1).
    const uint64_t cameraKey = sampleStream(ctx.stage, paths.pixel[i], paths.sample[i]);
    for (int j = 1; j < nC; ++j) {
      const BdptVertex& y = cam[j];
      if (!cameraBsdf[j].connectable() || !keep(1, j + 1)) continue;
      LightSample ls;
      if (!lights.sample(y.p, drawDouble(ctx.stage, cameraKey, bounceDim(uint32_t(j), kLightPick)),
                         drawFloat(ctx.stage, cameraKey, bounceDim(uint32_t(j), kLight1)),
                         drawFloat(ctx.stage, cameraKey, bounceDim(uint32_t(j), kLight2)), ls))
        continue;
      const Vec3 towardLightLocal = cameraBsdf[j].frame.toLocal(ls.direction);
      Color f;
      float toLight, toCamera;
      if (!cameraBsdf[j].connection(scratch.cameraBackLocal[size_t(j)], towardLightLocal, f, toLight, toCamera)) continue;
      BdptVertex lightVertex = lightVertexOf(scene, ls);
      const BdptVertex& z = lightVertex;  // its densities, set next, are read only by the MIS weight
      float pdfPosition, pdfDirection;
      lights.emissionDensity(z.emitter, z.primitive, z.ng, -ls.direction, pdfPosition, pdfDirection);
      lightVertex.pdfForward = pdfPosition;
      lightVertex.pdfReverse = 0;
      mis.build(cam.data(), j + 1, &lightVertex, 1, areaDensity(toLight, y, z), 0, areaDensity(pdfDirection, z, y),
                j - 1 >= 1 ? areaDensity(toCamera, y, cam[j - 1]) : 0.0f);
      mis.path.nextEventDensity = ls.pdfLight;
      mis.path.lightHittable = hittableLight(scene, z);
      mis.path.lightSeenByLightTracing = areaLight(scene, z);
      const float w = weight(mis, 1);
      const Color value = y.beta * f * ls.radiance * (w / (ls.delta ? 1.0f : ls.pdf));
      if (isBlack(value)) continue;
      const Vec3 origin = offsetOrigin(y.p, y.ng, ls.direction);
      // The light point pushed off its surface too (surface.h's shadowSegment says why).
      const Vec3 target = ls.environment ? origin + ls.direction * 1e7f
                                         : offsetOrigin(ls.position, ls.delta ? Vec3(0.0f) : ls.normal, -ls.direction);
      addConnection(sample, 1, j + 1, value, w, cameraIndex[size_t(j)], addExtra(lightVertex), &origin, target, 0, 0);
      if (ls.environment) rays.tfar[used - 1] = std::numeric_limits<float>::infinity();
    }

    // s >= 2, t >= 2: light vertex s - 1 to camera vertex t - 1.
    for (int s = 2; s <= nL; ++s) {
      const BdptVertex& z = light[s - 1];
      const VertexBsdf& zBsdf = lightBsdf[s - 1];
      if (!zBsdf.connectable()) continue;
      const Vec3 zOutLocal = scratch.lightBackLocal[size_t(s - 1)];
      for (int t = 2; t <= nC; ++t) {
        const BdptVertex& y = cam[t - 1];
        const VertexBsdf& yBsdf = cameraBsdf[t - 1];
        if (!keep(s, t)) continue;
        if (!yBsdf.connectable()) continue;
        const Vec3 d = z.p - y.p;
        const float d2 = dot(d, d);
        if (!(d2 > 0)) continue;
        const Vec3 w = d / std::sqrt(d2);
        Color fy, fz;
        float yToLight, yToCamera, zToLight, zToCamera;
        if (!yBsdf.connection(scratch.cameraBackLocal[size_t(t - 1)], yBsdf.frame.toLocal(w), fy, yToLight, yToCamera))
          continue;
        if (!zBsdf.connection(zBsdf.frame.toLocal(-w), zOutLocal, fz, zToLight, zToCamera)) continue;
        mis.build(cam.data(), t, light.data(), s, areaDensity(yToLight, y, z), areaDensity(zToLight, z, light[s - 2]),
                  areaDensity(zToCamera, z, y), t - 2 >= 1 ? areaDensity(yToCamera, y, cam[t - 2]) : 0.0f);
        mis.path.nextEventDensity = paths.lightNextEvent[i];
        mis.path.lightHittable = hittableLight(scene, light[0]);
        mis.path.lightSeenByLightTracing = areaLight(scene, light[0]);
        const float misWeight = weight(mis, s);
        const Color value = y.beta * fy * fz * z.beta * (std::abs(dot(z.ng, w)) / d2 * misWeight);
        if (isBlack(value)) continue;
        const Vec3 origin = offsetOrigin(y.p, y.ng, w);
        addConnection(sample, s, t, value, misWeight, cameraIndex[size_t(t - 1)], lightIndex[size_t(s - 1)], &origin,
                      offsetOrigin(z.p, z.ng, -w), 0, 0);
      }
    }

    // t = 1: light vertex s - 1 to a point on the lens, splatted where it lands.
    if (nL > 0) {
      const uint64_t lightKey = lightSubpathStream(ctx.stage, paths.pixel[i], paths.sample[i]);
      BdptVertex eye;
      eye.kind = kEyeVertex;
      eye.p = camera.lensPoint(drawFloat(ctx.stage, lightKey, kDimLensX), drawFloat(ctx.stage, lightKey, kDimLensY));
      eye.ng = camera.forward();
      eye.pdfForward = 1;
      int32_t eyeIndex = 0;  // the lens point's extra vertex, added with the sample's first splat
      for (int s = 1; s <= nL; ++s) {
        const BdptVertex& z = light[s - 1];
        if (!keep(s, 1)) continue;
        if (s == 1 ? !(z.kind == kLightVertex && areaLight(scene, z)) : !lightBsdf[s - 1].connectable()) continue;
        const Vec3 d = z.p - eye.p;
        const float d2 = dot(d, d);
        if (!(d2 > 0)) continue;
        const Vec3 w = d / std::sqrt(d2);
        const float cosCamera = camera.cosToAxis(w);
        float fx, fy;
        if (!(cosCamera > 0) || !camera.projectFrom(eye.p, z.p, fx, fy) || !(fx >= 0 && fx < float(width)) ||
            !(fy >= 0 && fy < float(height)))
          continue;
        Color fz;
        float zToLight = 0, zToCamera;
        if (s == 1) {
          fz = lightVertexEmission(scene, z, -w);
          if (isBlack(fz)) continue;
        } else if (!lightBsdf[s - 1].connection(lightBsdf[s - 1].frame.toLocal(-w),
                                                scratch.lightBackLocal[size_t(s - 1)], fz, zToLight, zToCamera)) {
          continue;
        }
        const float cameraPdf = cameraDirectionDensity(camera, width, height, w);
        mis.build(&eye, 1, light.data(), s, areaDensity(cameraPdf, eye, z),
                  s >= 2 ? areaDensity(zToLight, z, light[s - 2]) : 0.0f, 0, 0);
        mis.path.nextEventDensity = paths.lightNextEvent[i];
        mis.path.lightHittable = hittableLight(scene, light[0]);
        mis.path.lightSeenByLightTracing = areaLight(scene, light[0]);
        // The camera's importance over the strategy's density of the lens point: ppu^2 / (cos^3 W H).
        const float importance = ppu * ppu / (cosCamera * cosCamera * cosCamera * float(width) * float(height));
        const float misWeight = weight(mis, s);
        const Color value = z.beta * fz * (std::abs(dot(z.ng, w)) / d2 * importance * misWeight);
        if (isBlack(value)) continue;
        const Vec3 origin = offsetOrigin(z.p, z.ng, -w);
        if (eyeIndex == 0) eyeIndex = addExtra(eye);
        addConnection(sample, s, 1, value, misWeight, eyeIndex, lightIndex[size_t(s - 1)], &origin, eye.p, fx, fy);
      }
    }
    radiance[i] = Color(0.0f);
  }
  connections.resize(used);
}

}  // namespace erpt
