// The seed sampler of ERPT, PMC-ER and MLT (`--seeds path|bdpt`): the path tracer or BDPT, run
// over a set of samples with their contributions streamed out as seeds.
#pragma once

#include "erpt/erpt_settings.h"
#include "erpt/render.h"
#include "integrators/path/path_integrator.h"

namespace erpt {

struct RenderSetup;

// How the sampler places film positions, for the RenderSetup it runs in: drawn from the pixel
// filter (path) or uniform in the pixel (bdpt).
FilmMode seedFilmMode(const ChainOptions& o);
// Runs `sampler` over `samples` (the setup made with its seedFilmMode, for an image `height`
// pixels high): as tracePathSamples.
bool traceSeedSamples(SeedSampler sampler, int height, const RenderSetup& setup, const PathSampleSet& samples,
                      const PathTraceOutput& out, RenderStats& stats);
// A whole render by the sampler (the pilot pass, the direct pass).
RgbImage renderWithSeedSampler(const Scene& scene, const RenderSettings& s, RenderStats& stats);

}  // namespace erpt
