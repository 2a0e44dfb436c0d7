// Options that several integrators share, declared once (options.h): the perturbations of
// ERPT's mutation engine (erpt, mlt), the chains' budget, the direct-lighting pass (erpt,
// pmc-er, mlt) and the redistribution's deposits and noise filters (erpt, pmc-er).
#pragma once

#include <vector>

#include "erpt/erpt_settings.h"
#include "erpt/options.h"

namespace erpt {

OptionSpec mutationsPerPixelOption();
std::vector<OptionSpec> perturbationOptions();  // strategy, lens radius and shape, caustic angle
OptionSpec directSamplesOption();
OptionSpec seedsOption();  // --seeds path|bdpt
OptionSpec bidirectionalMutationOption();  // --bidir-mutation P
OptionSpec manifoldPerturbationOption();  // --manifold-perturbation P
std::vector<OptionSpec> depositOptions();  // deposit rule, proposed-mutations and consecutive-sample filters
OptionSpec chainMapsOption();  // --chain-maps: the mutations and acceptance maps (erpt, pmc-er, mlt)

// Appends `more` to `to` (for building a module's option list from these parts).
void addOptions(std::vector<OptionSpec>& to, const std::vector<OptionSpec>& more);

}  // namespace erpt
