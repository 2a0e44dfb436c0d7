// The options and statistics that every chain integrator shares (erpt, pmc-er, mlt): the
// mutation engine's perturbations, the chains' budget, the direct-lighting split, the seed
// sampler, the deposits and their filters, and the counts of the chain steps. Each integrator's
// own options live in its own struct (ErptSettings, PmcSettings, MltSettings).
#pragma once

#include <cstdint>

#include "erpt/mutation_kinds.h"

namespace erpt {

// Which mutation a chain uses: the paper's (caustic perturbation for paths L...SDE, lens
// perturbation otherwise), a fair coin when both apply, or one kind only (for tests: a chain
// whose path the kind cannot mutate stays where it is).
enum class MutationStrategy { Paper, Mixed, LensOnly, CausticOnly };

// The distribution of the lens perturbation's film position: a square of half-side
// lensRadius (ERPT) or a disk of radius lensRadius (PMC-ER).
enum class LensShape { Square, Disk };
// The caustic perturbation's angle: ERPT's 1/theta on [1e-4, 0.1] rad, or uniform in
// [0, theta_max] with theta_max from PMC-ER eq. 6 for an image move of lensRadius pixels.
enum class CausticAngle { Erpt, Veach };

// Where the chains' seeds (and the pilot, the direct pass, MLT's bootstrap) come from:
// the path tracer, or bidirectional path tracing (docs/bdpt.md, "Seeds").
enum class SeedSampler { Path, Bdpt };

struct ChainOptions {
  int mutationsPerPixel = 100;  // M (ERPT: sets e_d = n e_ave / M; MLT: its steps per pixel)
  float lensRadius = 4.5f;      // half-side of the lens perturbation's film square (9x9 pixels)
  MutationStrategy strategy = MutationStrategy::Paper;
  LensShape lensShape = LensShape::Square;
  CausticAngle causticAngle = CausticAngle::Erpt;
  bool expectedDeposit = false; // deposit (1 - q) at y and q at z instead of the paper's rule
  int directSamples = 64;       // >= 1: one-bounce paths by a direct-lighting pass (N spp); -1: the chains do all
  SeedSampler seeds = SeedSampler::Path;  // --seeds
  // The probability that a chain step (one that is not MLT's large step) proposes Veach's
  // bidirectional mutation instead of a perturbation (docs/bidirectional-mutation.md).
  float bidirectionalMutation = 0.0f;
  // The probability that a chain step proposes the manifold perturbation instead of the
  // strategy's perturbation, on the paths it applies to (a specular chain after the first
  // non-specular vertex: docs/manifold.md).
  float manifoldPerturbation = 0.0f;
  // Noise filters of the ERPT paper's section 4.4 (biased; off by default; erpt and pmc-er).
  int pmFilterRadius = -1;      // >= 0: proposed-mutations filter, box of (2r+1)^2 pixels; -1: off
  int maxConsecutive = 0;       // >= 1: consecutive-sample filter, N deposits in a row on a pixel; 0: off
  // --chain-maps: the render also returns the chains' proposals per pixel ("mutations") and
  // their mean acceptance probability ("acceptance"), by the proposals' film positions.
  bool chainMaps = false;
};

struct ChainStats {
  uint64_t seeds = 0;           // seeds offered to the chains (with energy, not left to the direct pass)
  uint64_t chains = 0;
  uint64_t mutations = 0;       // chain steps
  uint64_t proposed[kMutationKindCount] = {}, accepted[kMutationKindCount] = {};  // by MutationKind
  uint64_t rejected[kRejectReasonCount] = {};  // by RejectReason
  uint64_t deposits = 0;
  uint64_t inPlace[kInPlaceReasonCount] = {};  // seeds deposited where they are, by InPlaceReason
  uint64_t cappedSeeds = 0;     // seeds whose chain count hit ERPT's maxChainsPerSeed (their steps deposit more)
  uint64_t rays = 0;
  double pilotEnergy = 0;       // e_ave, the mean seed energy per pixel sample (ERPT's pilot; PMC-ER's pool)
  double depositEnergy = 0;     // e_d, the energy of one chain step
  double chainSeconds = 0;      // time in the chain loop
  uint64_t discardedDeposits = 0;   // thrown away by the consecutive-sample filter
  double discardedEnergy = 0;       // their luminance
};

// The ChainOptions of a RenderSettings (its `options`): chainOf(settings).field.
template <class Settings>
auto& chainOf(Settings& settings) {
  return settings.options.template get<ChainOptions>();
}

// The ChainStats of a RenderStats (its `own`): chainStatsOf(stats).field.
template <class Stats>
auto& chainStatsOf(Stats& stats) {
  return stats.own.template get<ChainStats>();
}

}  // namespace erpt
