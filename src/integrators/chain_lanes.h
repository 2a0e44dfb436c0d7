// The chain machine of ERPT: turns seeds into Markov chains (equal deposition, paper figure
// 6) and runs them as wavefronts over fixed-size SoA chain queues. Finished chains retire
// and their slots are refilled from the seeds before every step, so steps run with a full
// queue and memory stays bounded by the queues, whatever the image size.
//
// Lanes: a render on T threads runs T chain queues ("lanes"), each stepped by one thread from
// refill to deposit with no synchronisation with the others, which take the batch's chains
// from a shared counter as their slots free up. A chain's random stream is keyed by its number
// in the render, not by its lane or slot, and the lanes deposit into an ExactFilm, whose sums
// do not depend on the order of the adds; so the image is the same bits whichever lane ran a
// chain, for any thread count. (One queue for all threads, stepped stage by stage, spent a
// fork-join per stage per step and ran its deposits and refills on one thread: 1.3-1.5x on 2
// threads.)
#pragma once

#include <atomic>
#include <functional>
#include <mutex>
#include <memory>
#include <vector>

#include "core/byte_stream.h"

#include "integrators/chain_lane.h"
#include "integrators/lane_films.h"
#include "integrators/chain_settings.h"
#include "stages/chain_step.h"
#include "stages/chain_stages.h"
#include "erpt/render.h"
#include "tracer/tracer.h"

namespace erpt {

// Chain slots per lane: 1024 keeps a step's working set (chain and proposal vertices, ~1.4 MB)
// in one core's cache; larger queues measured up to 2x slower. Renders and bm_erpt's chain
// loop both use it.
constexpr size_t kErptLaneSlots = 1024;

class ChainLanes {
 public:
  struct Config {
    StepConfig step;
    ChainSettings chains;  // chain length, chain cap, the direct-light split, filters
    uint64_t seed = 0;         // the render's seed (chain and seed random streams)
    size_t laneSlots = kErptLaneSlots;  // chain slots of each lane
    double depositEnergy = 0;            // e_d (equal deposition)
    // When it turns true, consume() and finish() return false between steps, after every chain
    // left has deposited its remaining energy where it stands (depositUnfinished): the film
    // then holds the energy of every seed taken. (A render that rolls back to its last saved
    // state drops it with the rest of the film.)
    const std::atomic<bool>* stop = nullptr;
    // Called as the chains run with the chain steps taken so far by this machine, from one
    // lane's thread at a time.
    std::function<void(uint64_t steps)> onSteps = {};
    int lanes = 1;  // chain queues stepped at once (a render: its thread count)
    // The integrator's choices in every step (null: ERPT's; MLT's large steps, PMC-ER's mixture).
    const ProposalPolicy* policy = nullptr;
  };
  // Seeds deposited in place go to `film` (in seed order); the chains deposit into the
  // machine's own ExactFilm: image() is the sum of both.
  ChainLanes(const Tracer& tracer, const Config& config, Film& film, ChainStats& stats, StageTimes& times);
  ~ChainLanes();

  // Starts floor(U + e / (m e_d)) chains for each seed of the batch (detailed balance: one,
  // depositing e / m per step; at most Config::maxChainsPerSeed, each then depositing
  // e / (m cap)) and runs steps whenever the queue is full; on return every chain of the batch
  // is in the queue (or done). Seeds no chain can move (InPlaceReason), and every seed when
  // e_d = 0, are deposited at their own film position. Seeds longer than a chain holds are
  // folded in the batch (foldSeedTail). False: stopped (Config::stop).
  bool consume(SeedStore& batch);
  // MLT: starts one chain at every seed of `starts` (its start states, resampled by the caller),
  // each of settings' chainLength steps depositing `energyPerStep`, numbered in seed order, and
  // runs steps whenever a queue is full. No seed is deposited in place. False: stopped.
  bool startChains(const SeedStore& starts, float energyPerStep);
  // Runs the remaining chains to the end. False: stopped (Config::stop).
  bool finish();
  // The machine's state between batches with no chain in flight (after finish()): random
  // stream counters, deposit totals, tally, filter counts. load() also empties the queue.
  void save(ByteWriter& w) const;
  void load(ByteReader& r);
  // Everything deposited (the film given to the constructor and the chains' own film) over
  // `samplesPerPixel`.
  RgbImage image(double samplesPerPixel) const;
  // Split renders: the chains' film and the proposal tally become their totals over the
  // processes (`sum` adds doubles, as for Film::reduce).
  template <class Sum>
  void reduce(const Sum& sum) {
    exact_.reduce(sum);
    tallies_.reduce(sum);
  }
  // Chain steps taken so far (mutations, all lanes).
  uint64_t stepsTaken() const { return steps_.load(std::memory_order_relaxed); }
  // Energy added to the film so far (luminance), for tests.
  double depositedEnergy() const { return deposited_; }
  // The part of it deposited by seeds in place (InPlaceReason).
  double inPlaceEnergy() const { return inPlaceDeposited_; }
  // Complete proposals per pixel (with the proposed-mutations filter or the chain maps).
  const std::vector<uint32_t>& proposalTally() const { return tallies_.proposals; }
  const ProposalTallies& tallies() const { return tallies_; }

 private:
  const ChainSettings& settings() const { return config_.chains; }
  // Runs every lane on the pool's threads: until the batch's chains are all in a queue
  // (drain = false) or until no chain is left (drain = true). False: stopped.
  bool runLanes(bool drain);
  // Numbers the `chains` of pending_ (batch_ set) after those of earlier batches, runs the
  // lanes until all are in a queue, and lets go of the batch.
  bool runBatch(size_t chains);
  bool runLane(ChainLane& lane, ExactFilm& film, bool drain);
  // Loads the batch's next chains into the lane's free slots; true while chains of the batch
  // are still waiting for a slot afterwards.
  bool refill(ChainLane& lane);
  void step(ChainLane& lane, ExactFilm& film);
  // Lane totals (rays, energy, filter counts, stage times, large deposits) into the machine's.
  void mergeLanes();
  // Deposits `energy` (luminance) in the seed's colour at its film position, counted by `why`.
  void depositInPlace(const SeedStore& store, size_t seed, double energy, InPlaceReason why);
  bool stopped() const;
  // A stop: every chain in a queue deposits the energy of its steps left at its current path
  // (as if it were rejected from then on), and every chain of the batch still waiting for a
  // slot deposits all of its energy at its seed, into the film, in slot and chain order.
  void depositUnfinished();
  void countSteps(uint64_t steps);

  const Tracer& tracer_;
  Config config_;
  Film& film_;
  ChainStats& stats_;
  StageTimes& times_;
  ExactFilm exact_;
  // The lanes' own films (lane_films.h), added into exact_ after every run of the lanes; or
  // none, and the lanes share exact_.
  LaneFilms laneFilms_;
  std::vector<std::unique_ptr<ChainLane>> lanes_;
  StepCounters counters_;
  // Chains of the current batch: pending_[p] starts chains firstChain.. +copies of the batch,
  // whose numbers in the render start at chainBase_; lanes take them through nextChain_.
  struct PendingSeed {
    uint32_t seed, copies;
    float energyPerStep;  // luminance each step of these chains deposits
    size_t firstChain;
  };
  const SeedStore* batch_ = nullptr;
  std::vector<PendingSeed> pending_;
  std::vector<uint8_t> zeroF_;  // per seed starting chains: seedHasZeroContribution()
  std::atomic<size_t> nextChain_{0};
  size_t batchChains_ = 0;
  uint64_t chainBase_ = 0;
  uint64_t seedCounter_ = 0, chainCounter_ = 0;
  std::atomic<uint64_t> steps_{0};
  std::mutex progressMutex_;
  double deposited_ = 0, inPlaceDeposited_ = 0;
  ProposalTallies tallies_;
  DepositFilters filters_;
  std::vector<LargeDeposit> large_;
};

}  // namespace erpt
