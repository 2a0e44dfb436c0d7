// The mutation engine's unit: one Mutation per MutationKind (mutation_kinds.h), each defined in
// its own file under src/mutations/, in the spirit of Mitsuba 0.6's Mutator (suitability,
// sample, Q). A unit says
//   - when it applies to a path (its signature of vertex kinds),
//   - how a proposal starts: the perturbation it samples, the first ray, and the range of
//     vertices the proposal regenerates (written once into the proposal columns; the trace,
//     connect and accept stages read it from there),
//   - the path contribution f in its own measure (the measure it samples in),
//   - the ratio of transition densities T(z -> y) / T(y -> z) (0: the reverse move is
//     impossible), which the accept stage multiplies in.
// How a proposal advances through a specular chain is the same for every unit (the trace
// stage follows the current path's lobes from `cursor` in direction `walk` until it reaches
// regenLast, then connects to `connectTo`), so a unit describes it by those numbers only.
//
// Adding a mutation: an enum entry in mutation_kinds.h, one file in src/mutations/ defining its
// Mutation, and its line in mutation_table.cpp.
#pragma once

#include <limits>

#include "core/queues.h"
#include "mutations/chain_queues.h"
#include "kernels/erpt_path.h"
#include "mutations/step_config.h"
#include "tracer/tracer.h"

namespace erpt {

// What a mutation's start writes for one proposal.
struct ProposalStart {
  Vec3 origin, direction;  // the first ray
  float tnear = 0, tfar = std::numeric_limits<float>::infinity();
  float filmX = 0, filmY = 0;  // the proposal's film position when the start fixes it (lens)
  int cursor = 1;              // the vertex the first ray produces
  int walk = +1;               // +1: walks from the eye towards the light; -1: towards the eye
  int regenFirst = 1, regenLast = 0;  // vertices [regenFirst, regenLast] are regenerated
  // What the last regenerated vertex connects to: 0 the eye (its film position is found by
  // projection), k > 0 the fixed vertex k, -1 nothing (the walk reaches the light by tracing).
  int connectTo = -1;
  RejectReason reject = kRejectNone;  // set when the proposal is impossible from the start
};

// Everything a unit reads about the chain's current path y. (Lens starts read only the
// signature and the film position, straight from the chain's columns.)
struct CurrentPath {
  const PathVertex* vertices;
  const uint8_t* kinds;
  int n;
  float filmX, filmY;
};

// One chain slot as the accept stage hands it to a unit: the chain's and its proposal's rows,
// and scratch room for the paths y and z (kMaxChainVertices vertices each).
struct AcceptSlot {
  ChainQueue& chains;
  VertexQueue& chainVertices;
  ProposalQueue& proposals;
  const VertexQueue& proposalVertices;
  size_t i;
  PathVertex* y;
  PathVertex* z;
};
// A unit's verdict on a complete proposal: the acceptance probability q (0 with
// proposals.reason set when it cannot be accepted), and the proposal's colour as a deposit
// sees it with lum(f(z)) (`fzLum`, 0 when not known).
struct Acceptance {
  float q = 0;
  Color fz{0.0f};
  float fzLum = 0;
};

struct Mutation {
  MutationKind kind;
  // The unit whose contribution measure this one samples in (equal for units that differ only
  // in their perturbation's distribution): f and the fixed tail are cached per measure.
  MutationKind measure;
  bool (*applies)(const uint8_t* kinds, int n);
  // Starts the proposals of the slots in `range` whose proposal chose this unit (kind set,
  // state walking, perturbSize set by the mutate stage): samples each perturbation from the
  // chain's path y with the proposal's size, writes the first ray, the film position, the
  // walk direction and the regenerated range, or rejects (start_each.h's loop; lens.cpp makes
  // its eye rays in batches).
  void (*startRange)(const StepConfig& ctx, const ChainQueue& chains, const VertexQueue& chainVertices,
                     ProposalQueue& proposals, RayQueue& rays, IndexRange range);
  // First vertex of the fixed tail (erpt_path.h): f reads vertices up to it (inclusive) when
  // the tail is cached; n: no tail.
  int (*tailStart)(const uint8_t* kinds, int n);
  Color (*contribution)(const MeasureContext& c, const PathVertex* path, int n, float filmX, float filmY,
                        FixedTail* tail);
  // T(z -> y) / T(y -> z) for a proposal z of y made with `size`; 0 when z cannot propose y.
  float (*transitionRatio)(const MeasureContext& c, const CurrentPath& y, const CurrentPath& z, float size);
  // The accept stage's two calls, so that it has no branch on the kind: the acceptance of a
  // complete proposal, and, once accepted, moving the chain's path to it (the stage then sets
  // the film position and colour). The perturbations share one pair (perturbationAcceptance,
  // moveToPerturbation); MLT's large step has its own.
  Acceptance (*acceptance)(const StepConfig& ctx, const AcceptSlot& slot);
  void (*moveChain)(const AcceptSlot& slot, const Acceptance& accepted);
};

// The perturbations' acceptance: q = min(1, f(z) a(z) T(z -> y) / (f(y) a(y) T(y -> z))) on
// luminance in the unit's measure (a(z) / a(y): proposals.selection), with f and the fixed
// tail cached per measure in the chain's columns; and the move to z (its regenerated vertices).
Acceptance perturbationAcceptance(const StepConfig& ctx, const AcceptSlot& slot);
// The same verdict for a proposal whose f(z) was evaluated elsewhere (the lens contribution
// packet), with lum(f(y)) cached in the unit's measure; the paths' vertices and kinds are not
// loaded (null), so only for units whose transition ratio reads the film positions alone (lens).
Acceptance perturbationAcceptanceOf(const StepConfig& ctx, const AcceptSlot& slot, Color fz);
void moveToPerturbation(const AcceptSlot& slot, const Acceptance& accepted);
// The move of the units that make a whole path (the large step, the bidirectional mutation):
// every vertex of the proposal, its count and signature (large_step.cpp).
void moveToWholePath(const AcceptSlot& slot, const Acceptance& accepted);

// Marks slot i's proposal rejected for `why` and disables its ray, row `ray` of `rays`
// (mutate and trace stages; the trace stage's later bounces run in dense batches).
inline void rejectProposal(ProposalQueue& p, RayQueue& rays, size_t i, RejectReason why, size_t ray) {
  p.state[i] = kProposalRejected;
  p.reason[i] = why;
  disableRay(rays, ray);
}
inline void rejectProposal(ProposalQueue& p, RayQueue& rays, size_t i, RejectReason why) {
  rejectProposal(p, rays, i, why, i);
}

// Loads the current path of chain `slot` into `out` (kMaxChainVertices entries); returns its
// vertex count.
inline int loadChainPath(const ChainQueue& chains, const VertexQueue& vertices, size_t slot, PathVertex* out) {
  const int n = chains.vertexCount[slot];
  for (int j = 0; j < n; ++j) loadPathVertex(vertices, slot * kMaxChainVertices + size_t(j), out[j]);
  return n;
}

// The unit of a kind (None has no unit: a chain that cannot move).
const Mutation& mutationOf(MutationKind kind);
inline Color contributionFor(MutationKind kind, const MeasureContext& c, const PathVertex* path, int n, float filmX,
                             float filmY, FixedTail* tail = nullptr) {
  return kind == MutationKind::None ? Color(0.0f) : mutationOf(kind).contribution(c, path, n, filmX, filmY, tail);
}

// Lens perturbation (src/mutations/lens.cpp): the fixed vertex its walk connects to (-1: the
// walk reaches the light by tracing), and f in its measure.
int lensConnectionTarget(const uint8_t* kinds, int n);
Color lensContribution(const MeasureContext& c, const PathVertex* path, int n, float filmX, float filmY,
                       FixedTail* tail = nullptr);
// Caustic perturbation (src/mutations/caustic.cpp): the vertex s it starts from (the first
// non-specular vertex after vertex 1), or -1 when it does not apply (vertex 1 specular, the
// source the environment, the path too short); true for paths L...SDE; f in its measure.
int causticSource(const uint8_t* kinds, int n);
bool isCausticPath(const uint8_t* kinds, int n);
Color causticContribution(const MeasureContext& c, const PathVertex* path, int n, float filmX, float filmY,
                          FixedTail* tail = nullptr);
// PMC-ER eq. 6 (after Veach): the caustic angle range that moves the image by about `pixels`
// pixels: theta(d) |x0 - x1| / (sum of the segment lengths from the source to vertex 1),
// theta(d) the angle of d pixels at the eye.
float causticThetaMax(const MeasureContext& c, const CurrentPath& y, float pixels);

// Manifold perturbation (src/mutations/manifold.cpp): the fixed vertex c its chain walks to (a
// light, or a non-specular vertex), with the first non-specular vertex b in `first`, or -1 when
// it does not apply (no specular chain right after b); f in its measure without the chain's
// |d omega_b / dA_c|, which the manifold stage measures (proposals.measureRatio).
int manifoldChainEnd(const uint8_t* kinds, int n, int* first = nullptr);
Color manifoldContribution(const MeasureContext& c, const PathVertex* path, int n, float filmX, float filmY,
                           FixedTail* tail = nullptr);
// The manifold perturbation's coin (--manifold-perturbation P) for chain slot i: true with
// probability P on the paths it applies to. The signature decides, so the choice has the same
// probability at y and z and cancels in the acceptance ratio.
bool choosesManifold(const StepConfig& ctx, const ChainQueue& chains, size_t i, const uint8_t* kinds, int n);

// The family a strategy picks for a signature (Lens or Caustic, or None); the settings' lens
// shape and caustic angle then pick the unit. It depends on the signature only, which
// mutations preserve, so the selection probabilities are the same forwards and backwards and
// cancel in the acceptance ratio. u picks when `Mixed` has two choices.
MutationKind chooseMutation(MutationStrategy s, const uint8_t* kinds, int n, float u);

}  // namespace erpt
