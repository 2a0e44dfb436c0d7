// Options and statistics of `--integrator erpt` (Energy Redistribution Path Tracing).
#pragma once

#include <cstdint>

namespace erpt {

// Which mutation a chain uses: the paper's (caustic perturbation for paths L...SDE, lens
// perturbation otherwise), a fair coin when both apply, or one kind only (for tests: a chain
// whose path the kind cannot mutate stays where it is).
enum class MutationStrategy { Paper, Mixed, LensOnly, CausticOnly };

struct ErptSettings {
  int mutationsPerPixel = 100;  // M: sets e_d = n e_ave / M
  int chainLength = 100;        // m: steps of every chain
  float lensRadius = 4.5f;      // half-side of the lens perturbation's film square (9x9 pixels)
  MutationStrategy strategy = MutationStrategy::Paper;
  int pilotSpp = 4;             // samples per pixel of the pilot pass estimating e_ave
  bool expectedDeposit = false; // deposit (1 - q) at y and q at z instead of the paper's rule
  int directSamples = 64;       // >= 1: one-bounce paths by a direct-lighting pass (N spp); -1: ERPT does all
};

struct ErptStats {
  uint64_t seeds = 0;           // seeds offered to ERPT (with energy, not left to the direct pass)
  uint64_t chains = 0;
  uint64_t mutations = 0;       // chain steps
  uint64_t proposed[3] = {}, accepted[3] = {};  // by MutationKind (none, lens, caustic)
  uint64_t rejected[16] = {};   // by RejectReason
  uint64_t deposits = 0;
  uint64_t unhandledSeeds = 0;  // seeds no mutation could handle (too long, or no kind applies)
  uint64_t rays = 0;
  double pilotEnergy = 0;       // e_ave
  double depositEnergy = 0;     // e_d
  double erptSeconds = 0;       // time in the chain loop
};

}  // namespace erpt
