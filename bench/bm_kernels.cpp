// Kernels with an xsimd path against their scalar form.
#include <benchmark/benchmark.h>

#include "bench_support.h"
#include "models/camera.h"
#include "core/rng.h"

namespace erpt::bench {
namespace {

constexpr size_t kRays = 1 << 16;

struct CameraFixture {
  Scene scene = loadCornellBox();
  Camera camera{scene.camera, 256, 256};
  std::vector<float> fx, fy, dx, dy, dz, tn, tf;
  CameraFixture() : fx(kRays), fy(kRays), dx(kRays), dy(kRays), dz(kRays), tn(kRays), tf(kRays) {
    for (size_t i = 0; i < kRays; ++i) {
      fx[i] = 256 * uniformFloat(i, 0);
      fy[i] = 256 * uniformFloat(i, 1);
    }
  }
};

void BM_CameraRaysScalar(benchmark::State& state) {
  static CameraFixture f;
  for (auto _ : state)
    for (size_t i = 0; i < kRays; ++i) {
      Camera::Ray r = f.camera.generateRay(f.fx[i], f.fy[i]);
      f.dx[i] = r.direction.x;
      f.dy[i] = r.direction.y;
      f.dz[i] = r.direction.z;
      f.tn[i] = r.tnear;
      f.tf[i] = r.tfar;
    }
  state.counters["rays/s"] = benchmark::Counter(double(kRays) * state.iterations(), benchmark::Counter::kIsRate);
}

void BM_CameraRaysSimd(benchmark::State& state) {
  static CameraFixture f;
  for (auto _ : state)
    f.camera.generateRays(f.fx.data(), f.fy.data(), kRays, f.dx.data(), f.dy.data(), f.dz.data(), f.tn.data(),
                          f.tf.data());
  state.counters["rays/s"] = benchmark::Counter(double(kRays) * state.iterations(), benchmark::Counter::kIsRate);
}

BENCHMARK(BM_CameraRaysScalar);
BENCHMARK(BM_CameraRaysSimd);

}  // namespace
}  // namespace erpt::bench
