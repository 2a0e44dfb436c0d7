// `--integrator pssmlt`: primary-sample-space MLT (Kelemen et al. 2002) over the path tracer or
// BDPT, as Mitsuba 0.6's `pssmlt`; its engine is integrators/primary_sample_mlt.cpp.
#include "integrators/pssmlt/pssmlt_integrator.h"

#include <algorithm>
#include <cmath>

#include "erpt/chain_options.h"
#include "erpt/mlt_settings.h"
#include "integrators/chain_options.h"
#include "integrators/mlt/mlt_integrator.h"
#include "integrators/primary_sample_mlt.h"
#include "integrators/redistribution_parts.h"

namespace erpt {

IntegratorModule pssmltModule() {
  IntegratorModule m;
  m.name = "pssmlt";
  m.description =
      "primary-sample-space MLT (Kelemen et al. 2002) over the path tracer or BDPT, Kelemen's weights (docs/pssmlt.md)";
  m.options = {mutationsPerPixelOption(), directSamplesOption(), seedsOption()};
  addOptions(m.options, metropolisOptions());
  m.options.push_back(realOption("small-step",
                                 "Kelemen's largest small-step offset s2 of a primary sample (the smallest is s2 / 16)",
                                 1e-6, 0.5, [](auto& s) -> auto& { return pssmltOf(s).smallStep; }));
  m.sppOption = "mutations-per-pixel";  // Mitsuba's sample count, as for mlt
  m.validate = [](const RenderSettings& s) { validatePrimarySampleMlt(s, false); };
  m.render = [](const Scene& scene, const RenderSettings& s, RenderStats& stats) {
    return renderPrimarySampleMlt(scene, s, stats, false);
  };
  m.printSummary = [](const RenderStats& stats) { printPrimarySampleSummary("pssmlt", stats); };
  m.addStats = [](RenderStats& to, const RenderStats& from) { addPssmltStats(pssmltStatsOf(to), pssmltStatsOf(from)); };
  m.scaleTimedPass = [](const RenderSettings& s, RenderSettings& pass) {
    chainOf(pass).mutationsPerPixel = std::max(1, int(std::lround(double(chainOf(s).mutationsPerPixel) * pass.spp / s.spp)));
    scaleDirectSamples(s, pass);
  };
  return m;
}

}  // namespace erpt
