// The enumerations ERPT counts by: mutation kinds, why a proposal was rejected, why a seed's
// energy was deposited where it is instead of being redistributed. Every count array is
// sized from these (never a literal).
#pragma once

#include <cstdint>

namespace erpt {

// One entry per mutation unit (src/mutations/); None: no mutation (a chain that cannot move).
enum class MutationKind : uint8_t {
  None = 0,
  Lens,          // lens perturbation, film position uniform in a square (ERPT)
  LensDisk,      // lens perturbation, film position uniform in a disk (PMC-ER)
  Caustic,       // caustic perturbation, angle density 1/theta on [1e-4, 0.1] rad (ERPT)
  CausticVeach,  // caustic perturbation, angle uniform in [0, theta_max(path)] (PMC-ER eq. 6)
  LargeStep,     // MLT's independent proposal: a fresh path-tracer sample (large_step.h); no unit
  Bidirectional, // Veach's bidirectional mutation: a subpath deleted and regenerated from both ends
  Manifold,      // manifold perturbation: the film position moves, the specular chain after the first
                 // non-specular vertex is walked on its manifold to the next fixed vertex (docs/manifold.md)
  Count
};
constexpr int kMutationKindCount = int(MutationKind::Count);
const char* mutationName(MutationKind k);

// kProposalLarge: a large step waiting for its path-tracer sample (chain_step.h's ProposalSource).
enum ProposalState : uint8_t { kProposalWalking = 0, kProposalConnecting, kProposalComplete, kProposalRejected, kProposalLarge,
                                  kProposalBidirectional, kProposalManifold };
enum RejectReason : uint8_t {
  kRejectNone = 0,
  kRejectNoMutation,   // no mutation of the strategy applies to this path
  kRejectOffFilm,      // the proposal's film position lies outside the sampled film
  kRejectMissed,       // a traced ray missed (or escaped where the path had a surface)
  kRejectKindChanged,  // a vertex of another kind (specular / non-specular / light) was hit
  kRejectOccluded,     // the connection is blocked
  kRejectZero,         // the proposal carries no light (back of an emitter, BSDF zero, ...)
  kRejectIrreversible, // the reverse move is impossible (T(z -> y) = 0)
  kRejectCurrentZero,  // the chain's own path has no contribution in this mutation's measure
  kRejectByChance,     // valid proposal, not accepted by the coin flip
  kRejectNoCandidate,  // large step: the sample made no path of the chosen length and technique
  kRejectOutsideDomain,  // large step: a path the chains do not hold (too long, directional light, f = 0)
  kRejectNoWalk,       // manifold: the walk along the specular chain did not reach the proposed vertex
  kRejectReasonCount
};
const char* rejectReasonName(RejectReason r);

// Seeds whose energy is deposited at their own film position (their chains could not move, or
// there is no deposition energy to run chains with). Never lost, always counted.
enum InPlaceReason : uint8_t {
  kInPlaceNoMutation = 0,    // no mutation of the strategy applies to the path (or its folded form)
  kInPlaceZeroContribution,  // f of the seed is zero or not finite in a chosen mutation's measure
  kInPlaceNoDepositEnergy,   // e_d = 0: the pilot pass found no seed energy
  kInPlaceDirectionalLight,  // lit by a directional light: no mutation moves such paths yet
  kInPlaceFoldedChain,       // longer than a chain holds, and no mutation moves its vertices before the folded tail
  kInPlaceTooLong,           // MLT (which does not fold): more vertices than a chain holds
  kInPlaceOutsideLargeStep,  // MLT: the large step cannot make the path (W = 0), so it is outside the chains' domain
  kInPlaceReasonCount
};
const char* inPlaceReasonName(InPlaceReason r);

}  // namespace erpt
