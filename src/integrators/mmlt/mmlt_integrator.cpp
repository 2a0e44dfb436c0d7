// `--integrator mmlt`: multiplexed Metropolis light transport (Hachisuka, Kaplanyan and
// Dachsbacher 2014), as pbrt-v4's `mlt`: primary-sample-space chains, each keeping one path
// length, whose samples are one BDPT strategy drawn from the vector. Its engine is
// integrators/primary_sample_mlt.cpp.
#include "integrators/mmlt/mmlt_integrator.h"

#include <algorithm>
#include <cmath>

#include "erpt/chain_options.h"
#include "erpt/mlt_settings.h"
#include "integrators/chain_options.h"
#include "integrators/mlt/mlt_integrator.h"
#include "integrators/primary_sample_mlt.h"

namespace erpt {

IntegratorModule mmltModule() {
  IntegratorModule m;
  m.name = "mmlt";
  m.description = "multiplexed MLT (Hachisuka et al. 2014) over BDPT's strategies, as pbrt-v4's mlt (docs/pssmlt.md)";
  m.options = {mutationsPerPixelOption()};
  addOptions(m.options, metropolisOptions());
  m.options.push_back(realOption("sigma", "standard deviation of a small step's normal offset of a primary sample",
                                 1e-6, 0.5, [](auto& s) -> auto& { return pssmltOf(s).sigma; }));
  m.sppOption = "mutations-per-pixel";
  m.validate = [](const RenderSettings& s) { validatePrimarySampleMlt(s, true); };
  m.render = [](const Scene& scene, const RenderSettings& s, RenderStats& stats) {
    return renderPrimarySampleMlt(scene, s, stats, true);
  };
  m.printSummary = [](const RenderStats& stats) { printPrimarySampleSummary("mmlt", stats); };
  m.addStats = [](RenderStats& to, const RenderStats& from) { addPssmltStats(pssmltStatsOf(to), pssmltStatsOf(from)); };
  m.scaleTimedPass = [](const RenderSettings& s, RenderSettings& pass) {
    chainOf(pass).mutationsPerPixel = std::max(1, int(std::lround(double(chainOf(s).mutationsPerPixel) * pass.spp / s.spp)));
  };
  return m;
}

}  // namespace erpt
