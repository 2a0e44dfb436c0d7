// `--integrator bdpt`: wavefront bidirectional path tracing (docs/bdpt.md).
#pragma once

#include "erpt/integrators.h"
#include "erpt/render.h"

namespace erpt {

struct BdptSettings;
struct RenderSetup;
struct PathSampleSet;
struct PathTraceOutput;

RgbImage renderBdpt(const Scene& scene, const RenderSettings& settings, RenderStats& stats);

// BDPT over `samples` with the setup's camera, lights and stage context (made with
// FilmMode::SplatUnbiased: film positions uniform in the pixel): contributions to out.splat,
// and each as a seed to out.seeds (streamed batch by batch to out.seedSink when set): the
// `--seeds bdpt` of ERPT, PMC-ER and MLT. Returns false if out.stop turned true before every
// batch was done.
bool traceBdptSamples(const RenderSetup& setup, int height, const BdptSettings& settings, const PathSampleSet& samples,
                      const PathTraceOutput& out, RenderStats& stats);
IntegratorModule bdptModule();

}  // namespace erpt
