#include "integrators/chain_lanes.h"

#include <algorithm>
#include <chrono>
#include <memory>
#include <cmath>

#include "stages/chain_step.h"
#include "core/parallel.h"
#include "core/rng.h"
#include "integrators/seed_checks.h"

namespace erpt {

namespace {
constexpr uint64_t kChainStream = 0x636861696eull, kSeedStream = 0x73656564ull;

double secondsSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace


ChainLanes::ChainLanes(const Tracer& tracer, const Config& config, Film& film, ChainStats& stats, StageTimes& times)
    : tracer_(tracer),
      config_(config),
      film_(film),
      stats_(stats),
      times_(times),
      exact_(film.width(), film.height(), exactFilmUnit(config.depositEnergy),
             config.lanes > 1 && !LaneFilms::fit(size_t(config.lanes), film.width(), film.height())) {
  filters_.maxConsecutive = uint32_t(settings().maxConsecutive);
  tallies_.allocate(size_t(film.width()) * size_t(film.height()), settings().pmFilterRadius >= 0, settings().chainMaps);
  tallies_.attach(filters_);
  for (int l = 0; l < std::max(1, config.lanes); ++l) {
    lanes_.push_back(std::make_unique<ChainLane>(config.laneSlots));
    lanes_.back()->filters.maxConsecutive = filters_.maxConsecutive;
    tallies_.attach(lanes_.back()->filters);
  }
}

ChainLanes::~ChainLanes() = default;

bool ChainLanes::consume(SeedStore& batch) {
  batch_ = &batch;
  pending_.clear();
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
    foldSeedTail(config_.step, batch, i);
    // Drawn for every seed, so the chain numbering does not depend on which stay in place.
    const double u = uniformDouble(streamKey(config_.seed, kSeedStream, seedCounter_++), 0);
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
  times_.add("chain seed triage", secondsSince(triageStart));
  zeroF_.assign(started.size(), 0);
  forEachRange("chain seed check", started.size(), 64, [&](IndexRange r) {
    for (size_t k = r.begin; k < r.end; ++k) zeroF_[k] = seedHasZeroContribution(config_.step, batch, started[k].seed);
  }, &times_);
  size_t chains = 0;
  for (size_t k = 0; k < started.size(); ++k) {
    const Started& st = started[k];
    if (zeroF_[k]) {
      // What its chains would have deposited, at the seed's own film position.
      depositInPlace(batch, st.seed, double(st.energy) * m * st.copies, kInPlaceZeroContribution);
      continue;
    }
    pending_.push_back(PendingSeed{st.seed, st.copies, st.energy, chains});
    chains += st.copies;
  }
  return runBatch(chains);
}

bool ChainLanes::runBatch(size_t chains) {
  stats_.chains += chains;
  // The batch's chains are numbered in seed order, as one queue would have loaded them.
  chainBase_ = chainCounter_;
  chainCounter_ += chains;
  batchChains_ = chains;
  nextChain_ = 0;
  const bool done = runLanes(false);
  batch_ = nullptr;
  return done;
}

bool ChainLanes::startChains(const SeedStore& starts, float energyPerStep) {
  batch_ = &starts;
  pending_.clear();
  for (size_t i = 0; i < starts.size(); ++i) pending_.push_back(PendingSeed{uint32_t(i), 1, energyPerStep, i});
  stats_.seeds += starts.size();
  return runBatch(starts.size());
}

bool ChainLanes::finish() { return runLanes(true); }

bool ChainLanes::runLanes(bool drain) {
  if (laneFilms_.unit() != exact_.unit())  // the first run, or a state was loaded
    laneFilms_.reset(lanes_.size(), film_.width(), film_.height(), exact_.unit());
  std::atomic<bool> stop{false};
  forEachRange("chain chains", lanes_.size(), 1, [&](IndexRange r) {
    for (size_t l = r.begin; l < r.end; ++l)
      if (!runLane(*lanes_[l], laneFilms_.of(l, exact_), drain)) stop = true;
  });
  laneFilms_.mergeInto(exact_, &times_);
  mergeLanes();
  if (stop) depositUnfinished();
  // The large deposits wait for the end of the group of passes: when they are added to the
  // film they then do not depend on how far each lane had got when a batch's consume returned.
  if (drain && !stop) addLargeDeposits(large_, config_.step.measure.film, film_);
  return !stop;
}

bool ChainLanes::runLane(ChainLane& lane, ExactFilm& film, bool drain) {
  for (;;) {
    const bool waiting = refill(lane);
    if (drain) {
      bool active = false;
      for (size_t i = 0; i < lane.q.chains.size() && !active; ++i) active = lane.q.chains.stepsLeft[i] > 0;
      if (!active) return true;
    } else if (!waiting) {
      return true;  // the batch's chains are all in a queue: the next batch (or finish) runs them
    }
    if (stopped()) return false;
    uint64_t active = 0;
    for (size_t i = 0; i < lane.q.chains.size(); ++i) active += lane.q.chains.stepsLeft[i] > 0;
    step(lane, film);
    countSteps(active);
  }
}

void ChainLanes::countSteps(uint64_t steps) {
  const uint64_t total = steps_.fetch_add(steps, std::memory_order_relaxed) + steps;
  if (!config_.onSteps) return;
  std::unique_lock<std::mutex> lock(progressMutex_, std::try_to_lock);  // a lane already reporting: skip
  if (lock.owns_lock()) config_.onSteps(total);
}

void ChainLanes::depositUnfinished() {
  const FilmDensity& density = config_.step.measure.film;
  for (auto& lane : lanes_) {
    ChainQueue& q = lane->q.chains;
    for (size_t slot = 0; slot < q.size(); ++slot) {
      if (q.stepsLeft[slot] == 0) continue;
      const Color d = q.colorAt(slot) * float(double(q.energy[slot]) * q.stepsLeft[slot]);
      density.splat(q.filmX[slot], q.filmY[slot], [&](uint32_t pixel, float w) { film_.add(pixel, d * w); });
      deposited_ += luminance(d);
      q.stepsLeft[slot] = 0;
    }
  }
  if (batch_) {
    const size_t m = size_t(settings().chainLength);
    for (const PendingSeed& p : pending_) {
      const size_t from = std::max(p.firstChain, std::min(nextChain_.load(), batchChains_));
      if (from >= p.firstChain + p.copies) continue;
      const double energy = double(p.energyPerStep) * double(m) * double(p.firstChain + p.copies - from);
      deposited_ += depositSeedInPlace(config_.step.measure.film, *batch_, p.seed, energy, film_);
    }
    nextChain_ = batchChains_;
  }
  addLargeDeposits(large_, density, film_);
}

bool ChainLanes::stopped() const { return config_.stop && config_.stop->load(std::memory_order_relaxed); }

void ChainLanes::save(ByteWriter& w) const {
  w.put(config_.depositEnergy);
  w.put(seedCounter_), w.put(chainCounter_);
  w.put(deposited_), w.put(inPlaceDeposited_);
  counters_.save(w);
  w.put(filters_.discarded), w.put(filters_.discardedEnergy);
  tallies_.save(w);
  exact_.save(w);
}

void ChainLanes::load(ByteReader& r) {
  r.get(config_.depositEnergy);
  r.get(seedCounter_), r.get(chainCounter_);
  r.get(deposited_), r.get(inPlaceDeposited_);
  counters_.load(r);
  r.get(filters_.discarded), r.get(filters_.discardedEnergy);
  tallies_.load(r);
  exact_.load(r);
  large_.clear();
  for (auto& lane : lanes_) std::fill(lane->q.chains.stepsLeft.begin(), lane->q.chains.stepsLeft.end(), 0u);
  pending_.clear();
  batchChains_ = 0;
  nextChain_ = 0;
  batch_ = nullptr;
}

RgbImage ChainLanes::image(double samplesPerPixel) const {
  RgbImage img = film_.resolve(samplesPerPixel);
  exact_.addTo(img, samplesPerPixel);
  return img;
}

bool ChainLanes::refill(ChainLane& lane) {
  auto start = std::chrono::steady_clock::now();
  ChainQueue& q = lane.q.chains;
  size_t free = 0;
  for (size_t slot = 0; slot < q.size(); ++slot) free += q.stepsLeft[slot] == 0;
  const size_t next = nextChain_.load(std::memory_order_relaxed);
  if (free > 0 && next < batchChains_) {
    // At most a fair share of the chains still waiting, so that the last ones of a batch
    // spread over the lanes instead of keeping one lane busy while the others finish.
    const size_t share = (batchChains_ - next + lanes_.size() - 1) / lanes_.size();
    const size_t take = std::min(free, std::max<size_t>(share, 16));
    size_t k = nextChain_.fetch_add(take);
    const size_t end = std::min(k + take, batchChains_);
    if (k < end) {
      // The seed entry holding chain k, then onwards.
      size_t p = size_t(std::upper_bound(pending_.begin(), pending_.end(), k,
                                         [](size_t c, const PendingSeed& e) { return c < e.firstChain; }) -
                        pending_.begin()) - 1;
      for (size_t slot = 0; slot < q.size() && k < end; ++slot) {
        if (q.stepsLeft[slot] > 0) continue;
        while (k >= pending_[p].firstChain + pending_[p].copies) ++p;
        loadChainFromSeed(q, lane.q.chainVertices, slot, *batch_, pending_[p].seed,
                          streamKey(config_.seed, kChainStream, chainBase_ + k), uint32_t(settings().chainLength),
                          pending_[p].energyPerStep);
        ++k;
      }
    }
  }
  lane.times.add("chain refill", secondsSince(start));
  return nextChain_.load(std::memory_order_relaxed) < batchChains_;
}

void ChainLanes::depositInPlace(const SeedStore& store, size_t seed, double energy, InPlaceReason why) {
  ++stats_.inPlace[why];
  const double added = depositSeedInPlace(config_.step.measure.film, store, seed, energy, film_);
  deposited_ += added;
  inPlaceDeposited_ += added;
}

void ChainLanes::step(ChainLane& lane, ExactFilm& film) {
  lane.step(tracer_, config_.step, config_.policy, counters_, &film);
}

void ChainLanes::mergeLanes() {
  ChainLane::Totals totals;
  // Thread-seconds of the lanes, averaged: about the wall time each stage took.
  for (auto& lane : lanes_) lane->takeTotals(totals, times_, 1.0 / double(lanes_.size()), large_);
  stats_.rays += totals.rays;
  deposited_ += totals.deposited;
  filters_.discarded += totals.discarded;
  filters_.discardedEnergy += totals.discardedEnergy;
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
