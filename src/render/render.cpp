#include "erpt/render.h"

#include <chrono>

#include "direct_integrator.h"
#include "erpt_integrator.h"
#include "path_integrator.h"

namespace erpt {

RenderSettings resolveSettings(const Scene& scene, RenderSettings s) {
  if (s.width <= 0) s.width = scene.film.width;
  if (s.height <= 0) s.height = scene.film.height;
  if (s.spp <= 0) s.spp = scene.integrator.spp;
  if (s.maxDepth == -2) s.maxDepth = scene.integrator.maxDepth;
  if (!s.filterSet) s.filter = scene.film.filter;
  return s;
}

const char* integratorNames() { return "path, direct, erpt"; }

RgbImage render(const Scene& scene, const RenderSettings& requested, RenderStats& stats) {
  RenderSettings s = resolveSettings(scene, requested);
  auto start = std::chrono::steady_clock::now();
  RgbImage image;
  if (s.integrator == "path")
    image = renderPath(scene, s, stats);
  else if (s.integrator == "erpt")
    image = renderErpt(scene, s, stats);
  else if (s.integrator == "direct")
    image = renderDirect(scene, s, stats);
  else
    throw UsageError("unknown integrator '" + s.integrator + "' (available: " + integratorNames() + ")");
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return image;
}

}  // namespace erpt
