#include "integrators/seed_sampler.h"

#include "erpt/bdpt_settings.h"
#include "integrators/bdpt/bdpt_integrator.h"
#include "render_setup.h"

namespace erpt {

FilmMode seedFilmMode(const ChainOptions& o) {
  return o.seeds == SeedSampler::Bdpt ? FilmMode::SplatUnbiased : FilmMode::Fis;
}

bool traceSeedSamples(SeedSampler sampler, int height, const RenderSetup& setup, const PathSampleSet& samples,
                      const PathTraceOutput& out, RenderStats& stats) {
  if (sampler == SeedSampler::Bdpt) return traceBdptSamples(setup, height, BdptSettings{}, samples, out, stats);
  return tracePathSamples(setup, samples, out, stats);
}

RgbImage renderWithSeedSampler(const Scene& scene, const RenderSettings& s, RenderStats& stats) {
  if (chainOf(s).seeds == SeedSampler::Bdpt) {
    RenderSettings bdpt = s;
    bdptOf(bdpt) = BdptSettings{};
    return renderBdpt(scene, bdpt, stats);
  }
  return renderPath(scene, s, stats);
}

}  // namespace erpt
