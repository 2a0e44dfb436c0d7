#include "erpt/erpt_chains.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "erpt/chain_step.h"
#include "erpt/rng.h"
#include "erpt/seed_checks.h"

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
  filters_.maxConsecutive = uint32_t(settings().maxConsecutive);
  if (settings().pmFilterRadius >= 0) {
    tally_.assign(size_t(film.width()) * size_t(film.height()), 0);
    filters_.proposalTally = &tally_;
  }
}

bool ErptChains::consume(const SeedStore& batch) {
  batch_ = &batch;
  pending_.clear();
  pendingNext_ = 0;
  const double ed = config_.depositEnergy;
  const double m = double(settings().chainLength);
  const bool detailedBalance = config_.step.settings.flow == FlowRule::DetailedBalance;
  // First the chain counts (most seeds start none: e / (m e_d) is small), then, for the seeds
  // that start chains only, whether their chains could move (f in each mutation's measure,
  // computed in parallel), so the check costs per chain, not per seed.
  struct Started {
    uint32_t seed, copies;
    float energy;
  };
  std::vector<Started> started;
  auto triageStart = std::chrono::steady_clock::now();
  for (size_t i = 0; i < batch.size(); ++i) {
    if (!seedForChains(batch, i, settings().directSamples > 0)) continue;
    const float e = luminance(batch.contribution(i));
    if (!(e > 0) || !std::isfinite(e)) continue;
    ++stats_.seeds;
    // Drawn for every seed, so the chain numbering does not depend on which stay in place.
    const float u = uniformFloat(streamKey(config_.seed, kSeedStream, seedCounter_++), 0);
    // The signature alone says whether a chain can hold and move the seed (cheap, every seed):
    // if not, or with no deposition energy, the seed's own X_f goes where it is.
    const InPlaceReason bySignature = seedSignatureReason(config_.step, batch, i);
    if (bySignature != kInPlaceReasonCount || (!detailedBalance && !(ed > 0))) {
      depositInPlace(batch, i, e, bySignature != kInPlaceReasonCount ? bySignature : kInPlaceNoDepositEnergy);
      continue;
    }
    uint32_t copies = detailedBalance ? 1 : chainsForSeed(e, m, ed, u);
    float energy = float(detailedBalance ? double(e) / m : ed);
    if (copies > uint32_t(settings().maxChainsPerSeed)) {
      // Same total energy (e in expectation became exactly e), fewer chains.
      copies = uint32_t(settings().maxChainsPerSeed);
      energy = float(double(e) / (m * copies));
      ++stats_.cappedSeeds;
    }
    if (copies > 0) started.push_back(Started{uint32_t(i), copies, energy});
  }
  times_.add("erpt seed triage", secondsSince(triageStart));
  zeroF_.assign(started.size(), 0);
  forEachRange("erpt seed check", started.size(), 64, [&](IndexRange r) {
    for (size_t k = r.begin; k < r.end; ++k) zeroF_[k] = seedHasZeroContribution(config_.step, batch, started[k].seed);
  }, &times_);
  for (size_t k = 0; k < started.size(); ++k) {
    const Started& st = started[k];
    if (zeroF_[k]) {
      // What its chains would have deposited, at the seed's own film position.
      depositInPlace(batch, st.seed, double(st.energy) * m * st.copies, kInPlaceZeroContribution);
      continue;
    }
    stats_.chains += st.copies;
    pending_.push_back(PendingSeed{st.seed, st.copies, st.energy});
  }
  refill();
  while (pendingNext_ < pending_.size()) {
    if (stopped()) return false;
    step();
    refill();
  }
  batch_ = nullptr;
  return true;
}

bool ErptChains::finish() {
  while (anyActive()) {
    if (stopped()) return false;
    step();
  }
  return true;
}

bool ErptChains::stopped() const { return config_.stop && config_.stop->load(std::memory_order_relaxed); }

void ErptChains::save(ByteWriter& w) const {
  w.put(config_.depositEnergy);
  w.put(seedCounter_), w.put(chainCounter_);
  w.put(deposited_), w.put(inPlaceDeposited_);
  counters_.save(w);
  w.put(filters_.discarded), w.put(filters_.discardedEnergy);
  w.putVector(tally_);
}

void ErptChains::load(ByteReader& r) {
  r.get(config_.depositEnergy);
  r.get(seedCounter_), r.get(chainCounter_);
  r.get(deposited_), r.get(inPlaceDeposited_);
  counters_.load(r);
  r.get(filters_.discarded), r.get(filters_.discardedEnergy);
  r.getVector(tally_, tally_.size());
  std::fill(q_.chains.stepsLeft.begin(), q_.chains.stepsLeft.end(), 0u);
  pending_.clear();
  pendingNext_ = 0;
  batch_ = nullptr;
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
                      streamKey(config_.seed, kChainStream, chainCounter_++), uint32_t(settings().chainLength), p.energyPerStep);
    if (--p.copiesLeft == 0) ++pendingNext_;
  }
  times_.add("erpt refill", secondsSince(start));
  return full;
}

void ErptChains::depositInPlace(const SeedStore& store, size_t seed, double energy, InPlaceReason why) {
  ++stats_.inPlace[why];
  const double added = depositSeedInPlace(config_.step.measure.film, store, seed, energy, film_);
  deposited_ += added;
  inPlaceDeposited_ += added;
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
