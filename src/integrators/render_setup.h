// What every integrator builds before its first sample: threads, the Embree scene, camera,
// pixel filter, light sampler, stage context, film, and the tiled pixel order.
#pragma once

#include <memory>
#include <vector>

#include "erpt/film.h"
#include "erpt/render.h"
#include "erpt/stages.h"
#include "erpt/tracer.h"
#include "pixel_order.h"

namespace erpt {

struct RenderSetup {
  // Whether this render's path tracer splats its samples (only `--integrator path` does).
  static bool splats(const RenderSettings& s) {
    const FilmMode m = filmModeFor(s.film, s.filter);
    return s.integrator == "path" && (m == FilmMode::Splat || m == FilmMode::SplatUnbiased);
  }

  ThreadPool pool;
  std::shared_ptr<const Tracer> sharedTracer;
  const Tracer& tracer;
  Camera camera;
  PixelFilter filter;
  // Where camera samples go in a pixel: drawn from the filter (Fis), uniform when splatting.
  PixelFilter sampling;
  FilmMode filmMode;  // Fis unless the path tracer splats
  LightSampler lights;
  StageContext ctx;
  Film film;
  std::vector<uint32_t> order;  // pixels in 16x16 tiles
  size_t totalSamples;          // order.size() * spp

  RenderSetup(const Scene& scene, const RenderSettings& s)
      : pool(s.threads),
        sharedTracer(s.tracer ? s.tracer : std::make_shared<const Tracer>(scene)),
        tracer(*sharedTracer),
        camera(scene.camera, s.width, s.height),
        filter(s.filter),
        sampling(splats(s) ? FilterKind::Box : s.filter),
        filmMode(splats(s) ? filmModeFor(s.film, s.filter) : FilmMode::Fis),
        lights(scene),
        ctx{scene, camera, sampling, lights, s.seed, s.width, s.spp, s.maxDepth},
        film(s.width, s.height),
        order(tiledPixelOrder(s.width, s.height)),
        totalSamples(order.size() * size_t(s.spp)) {}
};

}  // namespace erpt
