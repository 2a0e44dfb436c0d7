// ERPT stage kernels. Chain slot i owns row i of the chain, proposal, ray, hit, shadow-ray and
// deposit queues, and rows [i * kMaxChainVertices, +kMaxChainVertices) of the chain's and the
// proposal's vertex queues. One chain step (chain_step.h runs it) is
//   mutate -> (intersect -> trace)* -> connect -> accept -> deposit
// and every stage runs over an index range of slots (forEachRange spreads it over threads).
#pragma once

#include <atomic>
#include <vector>

#include "erpt/mutation.h"
#include "erpt/erpt_settings.h"
#include "erpt/exact_film.h"
#include "erpt/film.h"
#include "erpt/seeds.h"
#include "erpt/tracer.h"

namespace erpt {

// What every stage of a chain step reads: the scene's measure context and ERPT's settings
// (ErptSettings is the one place for the options and their defaults).
struct LargeStepModel;

struct ErptStepContext {
  MeasureContext measure;
  ErptSettings settings;
  // MLT: the large step's model, which the accept stage needs for W(y) (null: no large steps).
  const LargeStepModel* largeSteps = nullptr;
  // The mutation units the settings' lens shape and caustic angle choose for the two families.
  MutationKind lensKind() const { return settings.lensShape == LensShape::Disk ? MutationKind::LensDisk : MutationKind::Lens; }
  MutationKind causticKind() const {
    return settings.causticAngle == CausticAngle::Veach ? MutationKind::CausticVeach : MutationKind::Caustic;
  }
};

// A chain that has not deposited yet (consecutive-sample filter).
constexpr uint32_t kNoPixel = 0xffffffffu;

// Random dimensions of one chain step (stream key = the chain's key, dimension =
// step * kStepDims + use). Direction perturbations at vertex j use kDimPerturb + 2j, +1.
// kDimComponent: the mixture component (PMC-ER's radius), after the last perturbation's.
// kDimLargeStep: MLT's coin for a large step; a large step then draws its pixel, path length
// and technique from kDimStart1, kDimStart2 and kDimPerturb (no perturbation uses them then).
enum StepDim : uint32_t {
  kDimStrategy = 0, kDimAccept, kDimStart1, kDimStart2, kDimPerturb, kDimLargeStep = 28, kDimComponent = 30, kStepDims = 32
};
static_assert(kDimPerturb + 2 * kMaxChainVertices <= kDimLargeStep, "step dimensions overlap");
inline uint32_t stepDim(uint32_t step, uint32_t use) { return step * kStepDims + use; }

// Statistics the accept stage counts (summed over threads).
struct ErptCounters {
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
struct ErptQueues {
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
  explicit ErptQueues(size_t capacity);
  // Memory one slot takes in every queue above (their capacity's share).
  static size_t bytesPerSlot();
};

// Loads the current path of chain `slot` into `out` (kMaxChainVertices entries); returns its
// vertex count.
int loadChainPath(const ChainQueue& chains, const VertexQueue& vertices, size_t slot, PathVertex* out);

// Whether a path's f is zero or not finite in the measure of a mutation the strategy may pick
// for it (a chain standing there would accept anything).
bool pathHasZeroContribution(const ErptStepContext& ctx, const PathVertex* path, int n, float filmX, float filmY);

// Starts a chain in `slot` at seed `seed` of `store`: its vertices, film position, colour
// rgb(X_f) / lum(X_f), random stream `key`, `chainLength` steps to go, each depositing
// `energyPerStep` (luminance).
void loadChainFromSeed(ChainQueue& chains, VertexQueue& chainVertices, size_t slot, const SeedStore& store,
                       size_t seed, uint64_t key, uint32_t chainLength, float energyPerStep);

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

// Chooses each chain's mutation and perturbation size for a step (the mutate stage's first
// pass), and the ratio a(z) / a(y) of the selection probabilities of that choice, which the
// accept stage multiplies in. ERPT's rule (erptChooser: the strategy picks the family from the
// signature, the settings the unit and size; the choice does not depend on the film position,
// so the ratio is 1) is the default; PMC-ER's mixture over radii is the other (pmc_mixture.h).
class MutationChooser {
 public:
  virtual ~MutationChooser() = default;
  // For every slot of `range` with an active chain (resetProposal returned true): sets
  // proposals.mutation (None: rejectProposal with kRejectNoMutation), perturbSize, component
  // and state kProposalWalking.
  virtual void choose(const ErptStepContext& ctx, const ChainQueue& chains, ProposalQueue& proposals, RayQueue& rays,
                      IndexRange range) const = 0;
  // After connect, for complete proposals: proposals.selection (left at 1 by default).
  virtual void selectionRatios(const ChainQueue&, ProposalQueue&, IndexRange) const {}
};
const MutationChooser& erptChooser();

// Clears slot i's proposal for a new step; false (and the proposal rejected) when the chain
// is inactive.
bool resetProposal(const ChainQueue& chains, ProposalQueue& proposals, RayQueue& rays, size_t i);

// Chooses each active chain's mutation (`chooser`; null: erptChooser()) and starts it: the
// first ray of the proposal in `rays` (lens: the eye ray through the perturbed film position;
// caustic: the perturbed ray leaving the source vertex). Inactive chains and impossible
// proposals get a disabled ray.
void stageErptMutate(const ErptStepContext& ctx, const ChainQueue& chains, const VertexQueue& chainVertices,
                     ProposalQueue& proposals, RayQueue& rays, IndexRange range,
                     const MutationChooser* chooser = nullptr);

// Trace stage, after intersect: checks each walking proposal's hit against the vertex kind the
// current path has there, stores the new vertex, and either sets the next ray (through a
// specular chain, or along a perturbed direction) or, at the proposal's last regenerated
// vertex, the connection ray in `shadowRays` (row = slot). Returns how many proposals are
// still walking. `slotOf` (null: row k is slot k) maps rows of `rays` and `hits` to chain
// slots, for the dense batches of the walk's later bounces (chain_step.cpp compacts them).
size_t stageErptTrace(const ErptStepContext& ctx, const ChainQueue& chains, const VertexQueue& chainVertices,
                      ProposalQueue& proposals, VertexQueue& proposalVertices, RayQueue& rays, const HitQueue& hits,
                      RayQueue& shadowRays, IndexRange range, const uint32_t* slotOf = nullptr);

// Connect stage: the occlusion stream for the connection rays of `range`, then rejects the
// proposals whose connection is blocked. `slotOf` as for the trace stage: row k of
// `shadowRays` is slot slotOf[k]'s connection.
void stageErptConnect(const Tracer& tracer, RayQueue& shadowRays, ProposalQueue& proposals, IndexRange range,
                      const uint32_t* slotOf = nullptr);

// Accept stage: q = min(1, f(z) a(z) T(z -> y) / (f(y) a(y) T(y -> z))) on luminance in the
// mutation's measure (a(z) / a(y): proposals.selection), the coin, the step's deposit record(s) (erpt_deposit.cpp's rule), and the chain
// update.
void stageErptAccept(const ErptStepContext& ctx, ChainQueue& chains, VertexQueue& chainVertices,
                     ProposalQueue& proposals, const VertexQueue& proposalVertices, DepositQueue& deposits,
                     ErptCounters& counters, IndexRange range);

// Deposit records per chain slot: slot i owns rows [i * kDepositsPerStep, + kDepositsPerStep)
// of the deposit queue (the paper's rule fills one, expected values two).
constexpr size_t kDepositsPerStep = 2;

// A path's film position and colour rgb(f) / lum(f), as a deposit sees it.
struct StepDeposit {
  float filmX, filmY;
  Color color;
};
// The deposit rule (erpt_deposit.cpp): the records one step of a chain leaves in row i, from
// the path before the step, the proposal (colour black when rejected before acceptance), q,
// whether the chain moved, and the chain's energy per step. The paper's rule: e_d at the
// chain's path after the step; expected values (and detailed balance, which never moves):
// (1 - q) e at the path before and q e at the proposal.
void writeStepDeposits(const ErptSettings& s, const StepDeposit& before, const StepDeposit& proposal, float q,
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
  uint64_t discarded = 0;      // deposit records thrown away
  double discardedEnergy = 0;  // their luminance
};

// Split renders: a proposal tally becomes its total over the processes (`sum` as Film::reduce's).
template <class Sum>
void reduceTally(std::vector<uint32_t>& tally, const Sum& sum) {
  if (tally.empty()) return;
  std::vector<double> t(tally.begin(), tally.end());
  sum(t);
  for (size_t i = 0; i < t.size(); ++i) tally[i] = uint32_t(t[i]);
}

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
