// Options and statistics of `--integrator pmc-er` (population Monte Carlo energy
// redistribution, Lai, Fan, Chenney, Dyer; docs/pmc-er.md derives the rules used here).
#pragma once

#include <cstdint>
#include <vector>

#include "erpt/mutation_kinds.h"

namespace erpt {

// How a member's energy reaches the film during an iteration (docs/pmc-er.md).
//   EqualDeposition (paper figure 2): the member is a Metropolis chain; each of its N steps
//     deposits the same share of its energy at its current path (or expected values).
//   Balance (figure 3): the member never moves; each of its N proposals z receives its share
//     times q(y -> z), the rest of that share stays at y (detailed-balance deposits).
enum class PmcFlow { EqualDeposition, Balance };
// How the mixture weights alpha over the radii are chosen.
//   Region: a table over image regions, learned by an independent training population and
//     frozen; evaluated at y and z in the acceptance (f-invariant; the default).
//   Member: the paper's rule, per member from its own acceptances (state dependent: can bias).
//   Off: uniform weights for every member.
enum class PmcAdapt { Region, Member, Off };

constexpr int kMaxPmcRadii = 8;
constexpr int kAlphaBins = 10;  // alpha histogram bins over [0, 1]

struct PmcSettings {
  PmcFlow flow = PmcFlow::EqualDeposition;
  // Defaults chosen by measurement at equal time (docs/pmc-er.md, "Defaults by measurement");
  // the paper's were 16 mutations per member and radii 5, 10, 50.
  int population = 5000;          // members (chain slots)
  int mutationsPerMember = 4;     // N_equal / N_balance: steps of every member per iteration
  std::vector<float> radii{2, 5, 10};  // mixture components d, in pixels
  PmcAdapt adapt = PmcAdapt::Region;
  double resampleRate = 0.4;      // share of the population regenerated from the pool per iteration
  float alphaFloor = 0.05f;       // eps: no mixture weight drops below it
  float causticProb = 0.9f;       // gamma_caustic where the caustic perturbation applies
  int regionSize = 16;            // Region adaptation: square regions of this many pixels
  int trainIterations = 4;        // Region adaptation: iterations of the training population
  // When the pool is used up, the population iterates until a member holds at most this share
  // of its energy, then deposits the rest where it stands.
  double drainRemainder = 0.1;
};

struct PmcStats {
  uint64_t iterations = 0, drainIterations = 0, trainingIterations = 0;
  uint64_t population = 0;
  uint64_t requestedPopulation = 0;       // --population; `population` is it bounded by the pool (pixels x spp)
  uint64_t poolSize = 0, poolUsed = 0;    // stratified film positions: all, and traced
  double poolEnergy = 0;                  // luminance of the traced positions' seeds (e_ave = poolEnergy / poolUsed)
  uint64_t candidates = 0;                // pool positions that gave a member candidate
  uint64_t inPlaceSeeds = 0;              // seeds no mutation can move, deposited where they are
  uint64_t membersBorn = 0, eliminated = 0, split = 0;  // resampling: candidates that became members, members dropped, extra copies
  double energyRegenerated = 0;           // energy the candidates brought (luminance)
  double energyEliminated = 0;            // remaining energy of dropped members (made up by the survivors)
  double energyFinal = 0;                 // deposited where the members stood when the render ended
  uint64_t steps = 0;                     // member steps (mutations) of the render, N_mutations
  double depositEnergy = 0;               // e_d of eq. 4 from the pilot: E_total / N_mutations
  double meanDeposit = 0;                 // what a step deposited on average (luminance)
  int radiusCount = 0;
  float radii[kMaxPmcRadii] = {};
  uint64_t proposed[kMaxPmcRadii][kMutationKindCount] = {}, accepted[kMaxPmcRadii][kMutationKindCount] = {};
  double acceptanceSum[kMaxPmcRadii][kMutationKindCount] = {};
  uint64_t alphaHistogram[kMaxPmcRadii][kAlphaBins] = {};  // members (Member) or regions (Region) by alpha_k
  double resampleSeconds = 0, regenerateSeconds = 0, chainSeconds = 0, trainSeconds = 0;
};

// The PmcSettings of a RenderSettings (its `options`): pmcOf(settings).field.
template <class Settings>
auto& pmcOf(Settings& settings) {
  return settings.options.template get<PmcSettings>();
}

// The PmcStats of a RenderStats (its `own`): pmcStatsOf(stats).field.
template <class Stats>
auto& pmcStatsOf(Stats& stats) {
  return stats.own.template get<PmcStats>();
}

}  // namespace erpt
