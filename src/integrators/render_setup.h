// What every integrator builds before its first sample: threads, the Embree scene, camera,
// pixel filter, light sampler, stage context, film, and the tiled pixel order.
#pragma once

#include <memory>
#include <vector>

#include "core/parallel.h"
#include "models/film.h"
#include "erpt/render.h"
#include "stages/stages.h"
#include "tracer/tracer.h"
#include "pixel_order.h"

namespace erpt {

struct RenderSetup {
  ThreadPool pool;
  std::shared_ptr<const Tracer> sharedTracer;
  const Tracer& tracer;
  Camera camera;
  PixelFilter filter;
  // Where camera samples go in a pixel: drawn from the filter (Fis), uniform when splatting.
  PixelFilter sampling;
  FilmMode filmMode;  // Fis, or how the path tracer splats
  LightSampler lights;
  StageContext ctx;
  Film film;
  std::vector<uint32_t> order;  // pixels in 16x16 tiles
  size_t totalSamples;          // order.size() * spp

  // `film`: Fis, or Splat/SplatUnbiased for a path tracer that splats (never Auto).
  RenderSetup(const Scene& scene, const RenderSettings& s, FilmMode film = FilmMode::Fis)
      : pool(s.threads),
        sharedTracer(s.tracer ? s.tracer : std::make_shared<const Tracer>(scene)),
        tracer(*sharedTracer),
        camera(scene.camera, s.width, s.height),
        filter(s.filter),
        sampling(film == FilmMode::Fis ? s.filter : FilterKind::Box),
        filmMode(film),
        lights(scene),
        ctx{scene, camera, sampling, lights, s.seed, s.width, s.height, s.spp, s.maxDepth},
        film(s.width, s.height),
        order(tiledPixelOrder(s.width, s.height)),
        totalSamples(order.size() * size_t(s.spp)) {}
};

}  // namespace erpt
