#include "erpt/erpt_chains.h"

#include <chrono>
#include <cmath>

#include "erpt/chain_step.h"
#include "erpt/rng.h"

namespace erpt {

namespace {
constexpr size_t kGrain = 256;
constexpr uint64_t kChainStream = 0x636861696eull, kSeedStream = 0x73656564ull;

double secondsSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}
}  // namespace

ErptChains::ErptChains(const Tracer& tracer, const Config& config, Film& film, ErptStats& stats, StageTimes& times)
    : tracer_(tracer), config_(config), film_(film), stats_(stats), times_(times), q_(config.capacity) {
  filters_.maxConsecutive = config.maxConsecutive;
  if (config.tallyProposals) {
    tally_.assign(size_t(film.width()) * size_t(film.height()), 0);
    filters_.proposalTally = &tally_;
  }
}

bool ErptChains::takesSeed(const SeedStore& store, size_t i, bool excludeDirect) {
  // Eye, one surface vertex, light: a one-bounce path (two vertices: an emitter seen directly).
  return !excludeDirect || store.seeds.vertexCount[i] > 3;
}

InPlaceReason ErptChains::inPlaceReason(const SeedStore& store, size_t i) const {
  const uint32_t n = store.seeds.vertexCount[i];
  if (n > uint32_t(kMaxChainVertices)) return kInPlaceTooLong;
  PathVertex path[kMaxChainVertices];
  uint8_t kinds[kMaxChainVertices];
  for (uint32_t j = 0; j < n; ++j) {
    path[j] = loadVertex(store.vertices, store.seeds.vertexBegin[i] + j);
    kinds[j] = path[j].kind;
  }
  // Every mutation the strategy may pick for this signature (the choice depends on the
  // signature only, which mutations preserve) must see a path of positive, finite f: a chain
  // standing on a zero of its target would accept anything.
  const MutationKind choices[] = {chooseMutation(config_.step.settings.strategy, kinds, int(n), 0.0f),
                                  chooseMutation(config_.step.settings.strategy, kinds, int(n), 0.999f)};
  if (choices[0] == MutationKind::None && choices[1] == MutationKind::None) return kInPlaceNoMutation;
  for (MutationKind family : choices) {
    if (family == MutationKind::None) continue;
    const MutationKind kind = family == MutationKind::Lens ? config_.step.lensKind() : config_.step.causticKind();
    const float f = luminance(contributionFor(kind, config_.step.measure, path, int(n), store.seeds.filmX[i],
                                              store.seeds.filmY[i]));
    if (!(f > 0) || !std::isfinite(f)) return kInPlaceZeroContribution;
  }
  return kInPlaceReasonCount;
}

void ErptChains::consume(const SeedStore& batch) {
  batch_ = &batch;
  pending_.clear();
  pendingNext_ = 0;
  const double ed = config_.depositEnergy;
  const double m = config_.chainLength;
  const bool detailedBalance = config_.step.settings.flow == FlowRule::DetailedBalance;
  // Which seeds can start moving chains: f in each mutation's measure, in parallel.
  inPlace_.assign(batch.size(), uint8_t(kInPlaceReasonCount));
  forEachRange("erpt seed check", batch.size(), kGrain, [&](IndexRange r) {
    for (size_t i = r.begin; i < r.end; ++i)
      if (takesSeed(batch, i, config_.excludeDirect)) inPlace_[i] = uint8_t(inPlaceReason(batch, i));
  }, &times_);
  for (size_t i = 0; i < batch.size(); ++i) {
    if (!takesSeed(batch, i, config_.excludeDirect)) continue;
    const float e = luminance(batch.contribution(i));
    if (!(e > 0) || !std::isfinite(e)) continue;
    ++stats_.seeds;
    // The seed's random number is drawn for every seed, so chain numbering does not depend on
    // which seeds stay in place.
    const float u = uniformFloat(streamKey(config_.seed, kSeedStream, seedCounter_++), 0);
    if (inPlace_[i] != kInPlaceReasonCount) {
      depositInPlace(batch, i, InPlaceReason(inPlace_[i]));
      continue;
    }
    if (!detailedBalance && !(ed > 0)) {
      depositInPlace(batch, i, kInPlaceNoDepositEnergy);
      continue;
    }
    uint32_t copies = detailedBalance ? 1 : chainsForSeed(e, m, ed, u);
    float energy = float(detailedBalance ? double(e) / m : ed);
    if (copies > config_.maxChainsPerSeed) {
      // Same total energy (e in expectation became exactly e), fewer chains.
      copies = config_.maxChainsPerSeed;
      energy = float(double(e) / (m * copies));
      ++stats_.cappedSeeds;
    }
    if (copies == 0) continue;
    stats_.chains += copies;
    pending_.push_back(PendingSeed{uint32_t(i), copies, energy});
  }
  refill();
  while (pendingNext_ < pending_.size()) {
    step();
    refill();
  }
  batch_ = nullptr;
}

void ErptChains::finish() {
  while (anyActive()) step();
}

bool ErptChains::anyActive() const {
  for (size_t i = 0; i < q_.chains.size(); ++i)
    if (q_.chains.stepsLeft[i] > 0) return true;
  return false;
}

bool ErptChains::refill() {
  auto start = std::chrono::steady_clock::now();
  bool full = true;
  for (size_t slot = 0; slot < q_.chains.size(); ++slot) {
    if (q_.chains.stepsLeft[slot] > 0) continue;
    if (pendingNext_ >= pending_.size()) {
      full = false;
      break;
    }
    PendingSeed& p = pending_[pendingNext_];
    loadChainFromSeed(q_.chains, q_.chainVertices, slot, *batch_, p.seed,
                      streamKey(config_.seed, kChainStream, chainCounter_++), config_.chainLength, p.energyPerStep);
    if (--p.copiesLeft == 0) ++pendingNext_;
  }
  times_.add("erpt refill", secondsSince(start));
  return full;
}

void ErptChains::depositInPlace(const SeedStore& store, size_t seed, InPlaceReason why) {
  // The seed's own estimate X_f, which is what its chains deposit in expectation.
  const Color energy = store.contribution(seed);
  ++stats_.inPlace[why];
  deposited_ += luminance(energy);
  inPlaceDeposited_ += luminance(energy);
  config_.step.measure.film.splat(store.seeds.filmX[seed], store.seeds.filmY[seed],
                                  [&](uint32_t pixel, float w) { film_.add(pixel, energy * w); });
}

void ErptChains::step() {
  const size_t c = q_.chains.size();
  const ErptStepContext& ctx = config_.step;
  const ChainStep chainStep{tracer_, ctx, &times_, kGrain};
  const uint64_t rays = chainStep.run(q_, counters_);
  stats_.rays += rays;
  auto start = std::chrono::steady_clock::now();
  deposited_ += applyDeposits(q_.chains, q_.proposals, q_.deposits, IndexRange{0, c}, ctx.measure.film, film_, filters_);
  times_.add("erpt deposit", secondsSince(start));
  // Counters to stats.
  uint64_t steps = 0;
  for (int k = 0; k < kMutationKindCount; ++k) {
    stats_.proposed[k] = counters_.proposed[k];
    stats_.accepted[k] = counters_.accepted[k];
    steps += counters_.proposed[k];
  }
  for (int r = 0; r < kRejectReasonCount; ++r) stats_.rejected[r] = counters_.rejected[r];
  stats_.mutations = steps;
  stats_.discardedDeposits = filters_.discarded;
  stats_.discardedEnergy = filters_.discardedEnergy;
  stats_.deposits = steps;
}

}  // namespace erpt
