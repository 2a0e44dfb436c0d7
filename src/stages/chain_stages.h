// The chain engine's stage kernels (ERPT, PMC-ER and MLT run them). Chain slot i owns row i of the chain, proposal, ray, hit, shadow-ray and
// deposit queues, and rows [i * kMaxChainVertices, +kMaxChainVertices) of the chain's and the
// proposal's vertex queues. One chain step (chain_step.h runs it) is
//   mutate -> (intersect -> trace)* -> connect -> accept -> deposit
// and every stage runs over an index range of slots (forEachRange spreads it over threads).
#pragma once

#include <atomic>
#include <limits>
#include <vector>

#include "mutations/mutation.h"
#include "mutations/step_config.h"
#include "erpt/stage_times.h"
#include "core/parallel.h"
#include "models/exact_film.h"
#include "models/film.h"
#include "core/seeds.h"
#include "core/byte_stream.h"
#include "models/surface.h"
#include "tracer/tracer.h"

namespace erpt {

// A chain that has not deposited yet (consecutive-sample filter).
constexpr uint32_t kNoPixel = 0xffffffffu;

// Statistics the accept stage counts (summed over threads).
struct StepCounters {
  std::atomic<uint64_t> proposed[kMutationKindCount] = {}, accepted[kMutationKindCount] = {};  // by MutationKind
  std::atomic<uint64_t> rejected[kRejectReasonCount] = {};

  // Render state (checkpoints, the state a stopped render falls back to).
  void save(ByteWriter& w) const {
    for (int k = 0; k < kMutationKindCount; ++k) w.put(proposed[k].load()), w.put(accepted[k].load());
    for (int k = 0; k < kRejectReasonCount; ++k) w.put(rejected[k].load());
  }
  void load(ByteReader& r) {
    for (int k = 0; k < kMutationKindCount; ++k) proposed[k] = r.get<uint64_t>(), accepted[k] = r.get<uint64_t>();
    for (int k = 0; k < kRejectReasonCount; ++k) rejected[k] = r.get<uint64_t>();
  }
};

// Every queue one chain step reads or writes, for `capacity` chain slots (all free).
struct StepQueues {
  ChainQueue chains;
  ProposalQueue proposals;
  VertexQueue chainVertices, proposalVertices;
  RayQueue rays, shadowRays;
  HitQueue hits;
  DepositQueue deposits;
  // Dense batches (chain_step.cpp): the rays of the proposals still walking after the first
  // bounce, or of the connections, with the slot each row belongs to.
  RayQueue denseRays;
  HitQueue denseHits;
  std::vector<uint32_t> denseSlots;
  explicit StepQueues(size_t capacity);
  // Memory one slot takes in every queue above (their capacity's share).
  static size_t bytesPerSlot();
};

// Whether a path's f is zero or not finite in the measure of a mutation the strategy may pick
// for it (a chain standing there would accept anything).
bool pathHasZeroContribution(const StepConfig& ctx, const PathVertex* path, int n, float filmX, float filmY);

// Starts a chain in `slot` at seed `seed` of `store`: its vertices, film position, colour
// rgb(X_f) / lum(X_f), random stream `key`, `chainLength` steps to go, each depositing
// `energyPerStep` (luminance).
void loadChainFromSeed(ChainQueue& chains, VertexQueue& chainVertices, size_t slot, const SeedStore& store,
                       size_t seed, uint64_t key, uint32_t chainLength, float energyPerStep);

struct StepQueues;

// What an integrator decides in every chain step, the engine's one extension point besides the
// mutation units: each chain's mutation and perturbation size (the mutate stage's first pass),
// the ratio a(z) / a(y) of the selection probabilities of that choice, which the accept stage
// multiplies in, and the start of proposals no unit starts. ERPT's rule (erptChooser: the
// strategy picks the family from the signature, the settings the unit and size; the choice does
// not depend on the film position, so the ratio is 1) is the default; PMC-ER's mixture over
// radii (pmc_mixture.h) and MLT's large-step coin with its path-tracer proposals
// (mlt_integrator.cpp) are the others.
class ProposalPolicy {
 public:
  virtual ~ProposalPolicy() = default;
  // For every slot of `range` with an active chain (resetProposal returned true): sets
  // proposals.mutation (None: rejectProposal with kRejectNoMutation), perturbSize, component
  // and state kProposalWalking (started by the unit) or kProposalLarge (by startOwnProposals).
  virtual void choose(const StepConfig& ctx, const ChainQueue& chains, ProposalQueue& proposals, RayQueue& rays,
                      IndexRange range) const = 0;
  // After connect, for complete proposals: proposals.selection (left at 1 by default).
  virtual void selectionRatios(const ChainQueue&, ProposalQueue&, IndexRange) const {}
  // After the mutate stage, over the whole queue: the proposals chosen in state kProposalLarge,
  // each left complete (the whole proposed path in the slot's proposal vertex rows, its vertex
  // count, signature, film position, colour and W(z)) or rejected. Returns the rays it traced.
  virtual uint64_t startOwnProposals(const StepConfig&, StepQueues&, StageTimes*) const { return 0; }
};
const ProposalPolicy& erptChooser();

// Clears slot i's proposal for a new step; false (and the proposal rejected) when the chain
// is inactive.
bool resetProposal(const ChainQueue& chains, ProposalQueue& proposals, RayQueue& rays, size_t i);

// Chooses each active chain's mutation (`policy`; null: erptChooser()) and starts it: the
// first ray of the proposal in `rays` (lens: the eye ray through the perturbed film position;
// caustic: the perturbed ray leaving the source vertex). Inactive chains and impossible
// proposals get a disabled ray.
void stageChainMutate(const StepConfig& ctx, const ChainQueue& chains, const VertexQueue& chainVertices,
                     ProposalQueue& proposals, RayQueue& rays, IndexRange range,
                     const ProposalPolicy* policy = nullptr);

// Trace stage, after intersect: checks each walking proposal's hit against the vertex kind the
// current path has there, stores the new vertex, and either sets the next ray (through a
// specular chain, or along a perturbed direction) or, at the proposal's last regenerated
// vertex, the connection ray in `shadowRays` (row = slot). Returns how many proposals are
// still walking. `slotOf` (null: row k is slot k) maps rows of `rays` and `hits` to chain
// slots, for the dense batches of the walk's later bounces (chain_step.cpp compacts them).
size_t stageChainTrace(const StepConfig& ctx, const ChainQueue& chains, const VertexQueue& chainVertices,
                      ProposalQueue& proposals, VertexQueue& proposalVertices, RayQueue& rays, const HitQueue& hits,
                      RayQueue& shadowRays, IndexRange range, const uint32_t* slotOf = nullptr);

// Sets row i of `shadowRays` to the connection from vertex `from` to point `to` (already
// offset off its surface); `toInfinity` follows `dir` out of the scene instead.
inline void setConnectionRay(RayQueue& shadowRays, size_t i, const PathVertex& from, Vec3 to, bool toInfinity, Vec3 dir) {
  const Vec3 origin = offsetOrigin(from.p, from.ng, dir);
  if (toInfinity) return setRay(shadowRays, i, origin, dir, 0.0f, std::numeric_limits<float>::infinity());
  // Aimed at `to` itself (surface.h's shadowSegment says why), just short of it.
  const Vec3 span = to - origin;
  const float length = std::sqrt(dot(span, span));
  setRay(shadowRays, i, origin, span / length, 0.0f, length * (1 - 1e-4f));
}

// The chain slots whose proposal is in `state`, in slot order (the stages that take over some
// proposals after the mutate or trace stage: the bidirectional mutation's, the manifold stage).
inline std::vector<uint32_t> slotsInState(const ProposalQueue& proposals, uint8_t state) {
  std::vector<uint32_t> slots;
  for (size_t i = 0; i < proposals.size(); ++i)
    if (proposals.state[i] == state) slots.push_back(uint32_t(i));
  return slots;
}

// The bidirectional mutation's stage (chain_bidirectional.cpp), after the mutate stage: the
// proposals in state kProposalBidirectional draw their plan, walk from both ends in dense
// batches, connect, and leave complete with their acceptance ratio (proposals.ratio) or
// rejected. Returns the rays traced.
uint64_t stageChainBidirectional(const Tracer& tracer, const StepConfig& ctx, StepQueues& q, size_t grain,
                                 StageTimes* times);

// The manifold stage (chain_manifold.cpp), after the trace stage: the proposals in state
// kProposalManifold walk the current path's specular chain to their new first non-specular
// vertex and back, and leave complete (their chain's vertices regenerated, the ratio of its
// |d omega / dA| in proposals.measureRatio) or rejected. Returns the rays traced.
uint64_t stageChainManifold(const Tracer& tracer, const StepConfig& ctx, StepQueues& q, size_t grain, StageTimes* times);

// Connect stage: the occlusion stream for the connection rays of `range`, then rejects the
// proposals whose connection is blocked. `slotOf` as for the trace stage: row k of
// `shadowRays` is slot slotOf[k]'s connection.
void stageChainConnect(const Tracer& tracer, RayQueue& shadowRays, ProposalQueue& proposals, IndexRange range,
                      const uint32_t* slotOf = nullptr);

// Accept stage: q = min(1, f(z) a(z) T(z -> y) / (f(y) a(y) T(y -> z))) on luminance in the
// mutation's measure (a(z) / a(y): proposals.selection), the coin, the step's deposit record(s) (chain_deposit.cpp's rule), and the chain
// update.
void stageChainAccept(const StepConfig& ctx, ChainQueue& chains, VertexQueue& chainVertices,
                     ProposalQueue& proposals, const VertexQueue& proposalVertices, DepositQueue& deposits,
                     StepCounters& counters, IndexRange range);

// Deposit records per chain slot: slot i owns rows [i * kDepositsPerStep, + kDepositsPerStep)
// of the deposit queue (the paper's rule fills one, expected values two).
constexpr size_t kDepositsPerStep = 2;

// A path's film position and colour rgb(f) / lum(f), as a deposit sees it.
struct StepDeposit {
  float filmX, filmY;
  Color color;
};
// The deposit rule (chain_deposit.cpp): the records one step of a chain leaves in row i, from
// the path before the step, the proposal (colour black when rejected before acceptance), q,
// whether the chain moved, and the chain's energy per step. The paper's rule: e_d at the
// chain's path after the step; expected values (and detailed balance, which never moves):
// (1 - q) e at the path before and q e at the proposal.
void writeStepDeposits(const StepSettings& s, const StepDeposit& before, const StepDeposit& proposal, float q,
                       bool moved, float energy, DepositQueue& deposits, size_t i);
// Empties slot i's deposit records.
void clearStepDeposits(DepositQueue& deposits, size_t i);

// The deposit stage's noise filters (paper section 4.4; both biased, both off by default).
struct DepositFilters {
  // Consecutive-sample filter: once a chain's path has stayed on one pixel for this many steps
  // in a row, its deposits on that pixel are thrown away until it leaves. 0: off.
  uint32_t maxConsecutive = 0;
  // Proposed-mutations filter: when set, every complete proposal adds 1 to the pixel its film
  // position falls in (width x height entries); the image is rescaled at the end
  // (noise_filters.h).
  std::vector<uint32_t>* proposalTally = nullptr;
  // The acceptance map (--chain-maps): with the tally, every counted proposal adds its
  // acceptance probability q, in units of kAcceptanceUnit, to its pixel.
  std::vector<uint64_t>* acceptanceTally = nullptr;
  uint64_t discarded = 0;      // deposit records thrown away
  double discardedEnergy = 0;  // their luminance
};
constexpr double kAcceptanceUnit = 1.0 / 65536;

// The per-pixel counts of a chain machine's proposals (DepositFilters): how many went to each
// pixel (the proposed-mutations filter's tally and the mutations map) and the sum of their
// acceptance probabilities (the acceptance map). Integers, so the sums do not depend on the
// order of the adds. Empty when not asked for.
struct ProposalTallies {
  std::vector<uint32_t> proposals;
  std::vector<uint64_t> acceptance;

  void allocate(size_t pixels, bool counts, bool acceptanceToo) {
    proposals.assign(counts || acceptanceToo ? pixels : 0, 0);
    acceptance.assign(acceptanceToo ? pixels : 0, 0);
  }
  void attach(DepositFilters& f) {
    f.proposalTally = proposals.empty() ? nullptr : &proposals;
    f.acceptanceTally = acceptance.empty() ? nullptr : &acceptance;
  }
  void save(ByteWriter& w) const {
    w.putVector(proposals);
    w.putVector(acceptance);
  }
  void load(ByteReader& r) {
    r.getVector(proposals, proposals.size());
    r.getVector(acceptance, acceptance.size());
  }
  // Split renders: the totals over the processes (`sum` as Film::reduce's; exact below 2^53).
  template <class Sum>
  void reduce(const Sum& sum) {
    reduceCounts(proposals, sum);
    reduceCounts(acceptance, sum);
  }

 private:
  template <class T, class Sum>
  static void reduceCounts(std::vector<T>& counts, const Sum& sum) {
    if (counts.empty()) return;
    std::vector<double> t(counts.begin(), counts.end());
    sum(t);
    for (size_t i = 0; i < t.size(); ++i) counts[i] = T(t[i]);
  }
};

// Where the deposit stage of one of ERPT's chain lanes splats its records while other lanes
// do the same: an ExactFilm (sums independent of the order of the adds), and, for the rare
// records too large for it, a list of them to add to a double film afterwards in the order of
// (chain key, step, record): addLargeDeposits. Either way the image does not depend on which
// lane ran a chain, or when.
struct LargeDeposit {
  uint64_t key;
  uint32_t step, record;
  float x, y;
  Color energy;
};
struct ConcurrentDeposits {
  ExactFilm& film;
  std::vector<LargeDeposit>& large;
};

// Adds the deposit records of the slots in `range`, splatting each over the pixels the filter
// reaches, after the noise filters (which update the chains' run state; the proposal tally is
// counted atomically). To a Film: in slot order, for one thread (PMC-ER's population); to
// ConcurrentDeposits: from any number of lanes at once. Returns the total energy added
// (luminance).
double applyDeposits(ChainQueue& chains, const ProposalQueue& proposals, const DepositQueue& deposits, IndexRange range,
                     const FilmDensity& density, Film& film, DepositFilters& filters);
double applyDeposits(ChainQueue& chains, const ProposalQueue& proposals, const DepositQueue& deposits, IndexRange range,
                     const FilmDensity& density, ConcurrentDeposits& target, DepositFilters& filters);
// Sorts `large` by (key, step, record), splats it to `film` in that order and empties it.
void addLargeDeposits(std::vector<LargeDeposit>& large, const FilmDensity& density, Film& film);

}  // namespace erpt
