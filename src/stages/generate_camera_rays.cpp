#include "erpt/rng.h"
#include "erpt/stages.h"
#include "erpt/tracer.h"

namespace erpt {

uint64_t sampleKey(uint64_t seed, uint32_t pixel, uint32_t sample) { return streamKey(seed, pixel, sample); }

void stageGenerateCameraRays(const StageContext& ctx, const uint32_t* pixels, const uint32_t* samples, RayQueue& rays,
                             IndexRange range, float* filmX, float* filmY) {
  const uint32_t spp = uint32_t(ctx.spp);
  for (size_t i = range.begin; i < range.end; ++i) {
    uint32_t pixel = pixels[i], s = samples[i];
    uint64_t key = sampleKey(ctx.seed, pixel, s);
    // Sample s takes stratum s in x and a per-pixel permuted stratum in y.
    uint32_t pixelKey = uint32_t(streamKey(ctx.seed, pixel, ~0ull));
    float ux = (float(s) + uniformFloat(key, kDimFilmX)) / float(spp);
    float uy = (float(permuteIndex(s, spp, pixelKey)) + uniformFloat(key, kDimFilmY)) / float(spp);
    float fx = float(pixel % uint32_t(ctx.width)) + 0.5f + ctx.filter.sampleOffset(std::min(ux, 0x1.fffffep-1f));
    float fy = float(pixel / uint32_t(ctx.width)) + 0.5f + ctx.filter.sampleOffset(std::min(uy, 0x1.fffffep-1f));
    Camera::Ray r = ctx.camera.generateRay(fx, fy);
    if (filmX) {
      filmX[i] = fx;
      filmY[i] = fy;
    }
    setRay(rays, i, r.origin, r.direction, r.tnear, r.tfar);
  }
}

}  // namespace erpt
