#include "bench_support.h"

#include <algorithm>
#include <cmath>

#include "models/camera.h"
#include "core/rng.h"
#include "erpt/scene_loader.h"
#include "models/surface.h"
#include "tracer/tracer.h"
#include "core/warp.h"

namespace erpt::bench {

Scene loadCornellBox() { return loadScene(std::string(ERPT_SOURCE_DIR) + "/../shared/scenes/cornell-box/scene.xml"); }
Scene loadDefaultScene() { return loadScene(std::string(ERPT_SOURCE_DIR) + "/scenes/default/scene.xml"); }

namespace {
struct AreaSampler {
  const TriangleSoup& mesh;
  std::vector<double> cdf;
  explicit AreaSampler(const TriangleSoup& m) : mesh(m) {
    double sum = 0;
    for (uint32_t t = 0; t < m.triangleCount(); ++t) cdf.push_back(sum += length(m.faceNormal(t)));
    for (double& c : cdf) c /= sum;
  }
  SurfacePoint sample(float u0, float u1, float u2) const {
    uint32_t t = uint32_t(std::lower_bound(cdf.begin(), cdf.end(), double(u0)) - cdf.begin());
    t = std::min<uint32_t>(t, uint32_t(cdf.size() - 1));
    float b1, b2;
    squareToTriangle(u1, u2, b1, b2);
    return triangleSurfaceAt(mesh, t, b1, b2);
  }
};
}  // namespace

RayQueue makeRays(const Scene& scene, RaySet kind, size_t n, uint64_t seed) {
  RayQueue q;
  prepareRays(q, n);
  AreaSampler area(scene.mesh);
  if (kind == RaySet::Primary) {
    int side = int(std::ceil(std::sqrt(double(n))));
    Camera cam(scene.camera, side, side);
    size_t i = 0;
    for (int ty = 0; ty < side && i < n; ty += 16)
      for (int tx = 0; tx < side && i < n; tx += 16)
        for (int y = ty; y < std::min(side, ty + 16) && i < n; ++y)
          for (int x = tx; x < std::min(side, tx + 16) && i < n; ++x, ++i) {
            uint64_t key = streamKey(seed, i, 0);
            Camera::Ray r = cam.generateRay(x + uniformFloat(key, 0), y + uniformFloat(key, 1));
            setRay(q, i, r.origin, r.direction, r.tnear, r.tfar);
          }
    return q;
  }
  for (size_t i = 0; i < n; ++i) {
    uint64_t key = streamKey(seed, i, 1);
    SurfacePoint a = area.sample(uniformFloat(key, 0), uniformFloat(key, 1), uniformFloat(key, 2));
    if (kind == RaySet::Diffuse) {
      Vec3 local = squareToCosineHemisphere(uniformFloat(key, 3), uniformFloat(key, 4));
      Vec3 dir = Frame(a.geometricNormal).toWorld(local);
      setRay(q, i, offsetOrigin(a.position, a.geometricNormal, dir), dir, 0.0f, std::numeric_limits<float>::infinity());
    } else {
      SurfacePoint b = area.sample(uniformFloat(key, 5), uniformFloat(key, 6), uniformFloat(key, 7));
      Vec3 d = b.position - a.position;
      float len = length(d);
      Vec3 dir = len > 0 ? d / len : Vec3(0, 0, 1);
      setRay(q, i, a.position, dir, 1e-4f, len * (1 - 1e-4f));
    }
  }
  return q;
}

void benchmarkWholeRender(benchmark::State& state, const Scene& scene, const RenderSettings& settings,
                          const char* samplesName) {
  double rays = 0, samples = 0, seconds = 0;
  RenderStats stats;
  for (auto _ : state) {
    stats = RenderStats{};
    benchmark::DoNotOptimize(render(scene, settings, stats));
    rays += double(stats.rays);
    samples += double(stats.samples);
    seconds += stats.seconds;
  }
  state.counters["rays/s"] = rays / seconds;
  state.counters[samplesName] = samples / seconds;
  double total = 0;
  for (const auto& [name, t] : stats.stages.all()) total += t;
  for (const auto& [name, t] : stats.stages.all()) state.counters["share_" + name] = t / total;
}

}  // namespace erpt::bench
