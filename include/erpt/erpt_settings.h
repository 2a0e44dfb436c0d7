// Options and statistics of `--integrator erpt` (Energy Redistribution Path Tracing).
#pragma once

#include <cstdint>

#include "erpt/mutation_kinds.h"

namespace erpt {

// Which mutation a chain uses: the paper's (caustic perturbation for paths L...SDE, lens
// perturbation otherwise), a fair coin when both apply, or one kind only (for tests: a chain
// whose path the kind cannot mutate stays where it is).
enum class MutationStrategy { Paper, Mixed, LensOnly, CausticOnly };

// How a seed's energy flows (paper section 3). Equal deposition (3.2): floor(U + e / (m e_d))
// chains of m steps, each step depositing e_d at the chain's current path. Detailed balance
// (3.1, the paper's baseline): the seed x is mutated m times, never moves, and each mutation
// y_i receives e q(x -> y_i) / m; what did not flow stays at x.
enum class FlowRule { EqualDeposition, DetailedBalance };

// The distribution of the lens perturbation's film position: a square of half-side
// lensRadius (ERPT) or a disk of radius lensRadius (PMC-ER).
enum class LensShape { Square, Disk };
// The caustic perturbation's angle: ERPT's 1/theta on [1e-4, 0.1] rad, or uniform in
// [0, theta_max] with theta_max from PMC-ER eq. 6 for an image move of lensRadius pixels.
enum class CausticAngle { Erpt, Veach };

// Where the chains' seeds (and the pilot, the direct pass, MLT's bootstrap) come from:
// the path tracer, or bidirectional path tracing (docs/bdpt.md, "Seeds").
enum class SeedSampler { Path, Bdpt };

struct ErptSettings {
  int mutationsPerPixel = 100;  // M: sets e_d = n e_ave / M
  int chainLength = 100;        // m: steps of every chain
  float lensRadius = 4.5f;      // half-side of the lens perturbation's film square (9x9 pixels)
  MutationStrategy strategy = MutationStrategy::Paper;
  LensShape lensShape = LensShape::Square;
  CausticAngle causticAngle = CausticAngle::Erpt;
  int pilotSpp = 4;             // samples per pixel of the pilot pass estimating e_ave
  bool expectedDeposit = false; // deposit (1 - q) at y and q at z instead of the paper's rule
  int directSamples = 64;       // >= 1: one-bounce paths by a direct-lighting pass (N spp); -1: ERPT does all
  SeedSampler seeds = SeedSampler::Path;  // --seeds
  // The probability that a chain step (one that is not MLT's large step) proposes Veach's
  // bidirectional mutation instead of a perturbation (docs/bidirectional-mutation.md).
  float bidirectionalMutation = 0.0f;
  FlowRule flow = FlowRule::EqualDeposition;
  // Noise filters of section 4.4 (biased; off by default).
  int pmFilterRadius = -1;      // >= 0: proposed-mutations filter, box of (2r+1)^2 pixels; -1: off
  int maxConsecutive = 0;       // >= 1: consecutive-sample filter, N deposits in a row on a pixel; 0: off
  // --chain-maps: the render also returns the chains' proposals per pixel ("mutations") and
  // their mean acceptance probability ("acceptance"), by the proposals' film positions.
  bool chainMaps = false;
  // At most this many chains start from one seed; a seed that would start more (a tiny e_ave
  // makes e / (m e_d) explode) starts this many, each step depositing e / (m cap) instead of e_d.
  int maxChainsPerSeed = 4096;
};

struct ErptStats {
  uint64_t seeds = 0;           // seeds offered to ERPT (with energy, not left to the direct pass)
  uint64_t chains = 0;
  uint64_t mutations = 0;       // chain steps
  uint64_t proposed[kMutationKindCount] = {}, accepted[kMutationKindCount] = {};  // by MutationKind
  uint64_t rejected[kRejectReasonCount] = {};  // by RejectReason
  uint64_t deposits = 0;
  uint64_t inPlace[kInPlaceReasonCount] = {};  // seeds deposited where they are, by InPlaceReason
  uint64_t cappedSeeds = 0;     // seeds whose chain count hit maxChainsPerSeed (their steps deposit more)
  uint64_t rays = 0;
  double pilotEnergy = 0;       // e_ave
  double depositEnergy = 0;     // e_d
  double erptSeconds = 0;       // time in the chain loop
  uint64_t discardedDeposits = 0;   // thrown away by the consecutive-sample filter
  double discardedEnergy = 0;       // their luminance
};

// The ErptSettings of a RenderSettings (its `options`): erptOf(settings).field.
template <class Settings>
auto& erptOf(Settings& settings) {
  return settings.options.template get<ErptSettings>();
}

// The ErptStats of a RenderStats (its `own`): erptStatsOf(stats).field.
template <class Stats>
auto& erptStatsOf(Stats& stats) {
  return stats.own.template get<ErptStats>();
}

}  // namespace erpt
