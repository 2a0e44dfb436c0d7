// Options of `--integrator erpt` (Energy Redistribution Path Tracing).
#pragma once

#include <cstdint>

#include "erpt/chain_options.h"

namespace erpt {

// How a seed's energy flows (paper section 3). Equal deposition (3.2): floor(U + e / (m e_d))
// chains of m steps, each step depositing e_d at the chain's current path. Detailed balance
// (3.1, the paper's baseline): the seed x is mutated m times, never moves, and each mutation
// y_i receives e q(x -> y_i) / m; what did not flow stays at x.
enum class FlowRule { EqualDeposition, DetailedBalance };

// ERPT's own options; the ones it shares with pmc-er and mlt are ChainOptions (chainOf).
struct ErptSettings {
  int chainLength = 100;        // m: steps of every chain
  int pilotSpp = 4;             // samples per pixel of the pilot pass estimating e_ave
  FlowRule flow = FlowRule::EqualDeposition;
  // At most this many chains start from one seed; a seed that would start more (a tiny e_ave
  // makes e / (m e_d) explode) starts this many, each step depositing e / (m cap) instead of e_d.
  int maxChainsPerSeed = 4096;
};

// The ErptSettings of a RenderSettings (its `options`): erptOf(settings).field.
template <class Settings>
auto& erptOf(Settings& settings) {
  return settings.options.template get<ErptSettings>();
}

}  // namespace erpt
