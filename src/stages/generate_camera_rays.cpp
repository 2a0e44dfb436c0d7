#include <algorithm>
#include <cmath>
#include <vector>

#include "core/rng.h"
#include "kernels/pixel_strata.h"
#include "stages/stages.h"
#include "tracer/tracer.h"

namespace erpt {

uint64_t sampleKey(uint64_t seed, uint32_t pixel, uint32_t sample) { return streamKey(seed, pixel, sample); }

void startPath(PathQueue& paths, uint32_t id, uint64_t key, uint32_t pixel, uint32_t sample) {
  paths.pixel[id] = pixel;
  paths.sample[id] = sample;
  paths.key[id] = key;
  paths.depth[id] = 1;
  paths.throughputSet(id, Color(1.0f));
  paths.radianceSet(id, Color(0.0f));
  paths.prevPdf[id] = 0;
  paths.pLength[id] = 1;
  paths.etaSquared[id] = 1;
  paths.lastVertex[id] = -1;
}

void stageGenerateCameraRays(const StageContext& ctx, const uint32_t* pixels, const uint32_t* samples, RayQueue& rays,
                             IndexRange range, float* filmX, float* filmY) {
  const uint32_t spp = uint32_t(ctx.spp);
  // Film positions go to the caller's columns, or to scratch space when it does not keep them.
  std::vector<float> scratch;
  if (!filmX) {
    scratch.resize(2 * range.size());
    filmX = scratch.data() - range.begin;
    filmY = scratch.data() + range.size() - range.begin;
  }
  if (ctx.replay) {
    // Primary sample space: the film position is the chain's first two numbers, over the film.
    for (size_t i = range.begin; i < range.end; ++i) {
      // (A product that rounds up to the film's edge stays inside it.)
      filmX[i] = std::min(drawFloat(ctx, samples[i], kDimFilmX) * float(ctx.width), std::nextafter(float(ctx.width), 0.0f));
      filmY[i] = std::min(drawFloat(ctx, samples[i], kDimFilmY) * float(ctx.height), std::nextafter(float(ctx.height), 0.0f));
    }
  } else {
    // Sample s takes a stratum in x and one in y, each by its own per-pixel permutation (a
    // Latin hypercube). Permuting x too makes every sample uniform over the pixel on its own,
    // so the first k of the spp samples are an unbiased render at k spp (sample passes).
    // Samples from spp on (PMC-ER's pool under a time budget) stratify block by block: block
    // b = s / spp is another Latin hypercube of spp strata with its own permutations.
    pixelStrata(ctx.seed, spp, kDimFilmX, kDimFilmY, pixels + range.begin, samples + range.begin, range.size(),
                filmX + range.begin, filmY + range.begin);
    for (size_t i = range.begin; i < range.end; ++i) {
      const uint32_t pixel = pixels[i];
      filmX[i] = float(pixel % uint32_t(ctx.width)) + 0.5f + ctx.filter.sampleOffset(std::min(filmX[i], 0x1.fffffep-1f));
      filmY[i] = float(pixel / uint32_t(ctx.width)) + 0.5f + ctx.filter.sampleOffset(std::min(filmY[i], 0x1.fffffep-1f));
    }
  }
  const size_t b = range.begin;
  ctx.camera.generateRays(filmX + b, filmY + b, range.size(), rays.dirX.data() + b, rays.dirY.data() + b,
                          rays.dirZ.data() + b, rays.tnear.data() + b, rays.tfar.data() + b);
  const Vec3 eye = ctx.camera.position();
  std::fill(rays.orgX.begin() + b, rays.orgX.begin() + range.end, eye.x);
  std::fill(rays.orgY.begin() + b, rays.orgY.begin() + range.end, eye.y);
  std::fill(rays.orgZ.begin() + b, rays.orgZ.begin() + range.end, eye.z);
  if (!ctx.camera.hasLens()) return;
  for (size_t i = range.begin; i < range.end; ++i) {
    const uint64_t key = sampleStream(ctx, pixels[i], samples[i]);
    Vec3 origin, direction = rays.dirAt(i);
    ctx.camera.throughLens(drawFloat(ctx, key, kDimLensX), drawFloat(ctx, key, kDimLensY), origin, direction, rays.tnear[i],
                           rays.tfar[i]);
    rays.orgX[i] = origin.x, rays.orgY[i] = origin.y, rays.orgZ[i] = origin.z;
    rays.dirX[i] = direction.x, rays.dirY[i] = direction.y, rays.dirZ[i] = direction.z;
  }
}

}  // namespace erpt
