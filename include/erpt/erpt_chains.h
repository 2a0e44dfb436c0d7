// The chain machine of ERPT: turns seeds into Markov chains (equal deposition, paper figure
// 6) and runs them as a wavefront over a fixed-size SoA chain queue. Finished chains retire
// and their slots are refilled from the seeds before every step, so steps run with a full
// queue and memory stays bounded by the queue, whatever the image size.
#pragma once

#include <atomic>
#include <vector>

#include "erpt/byte_stream.h"

#include "erpt/erpt_stages.h"
#include "erpt/render.h"
#include "erpt/tracer.h"

namespace erpt {

// Chain slots for a render on `threads` threads: 1024 per thread keeps a step's working set
// (chain and proposal vertices, ~1.4 MB per thread) in cache; larger queues measured up to 2x
// slower. Renders and bm_erpt's chain loop both use it.
inline size_t erptChainSlots(int threads) { return size_t(1024) * size_t(threads < 1 ? 1 : threads); }

class ErptChains {
 public:
  // What the chain machine needs besides the ERPT settings (which come with the step
  // context: chain length, flow rule, filters, chain cap, the direct-light split).
  struct Config {
    ErptStepContext step;
    uint64_t seed = 0;         // the render's seed (chain and seed random streams)
    size_t capacity = 1024;    // chain slots (erptChainSlots)
    double depositEnergy = 0;  // e_d (equal deposition)
    // When it turns true, consume() and finish() return false between steps (the render then
    // falls back to its last saved state: the chains left are dropped, never half-deposited).
    const std::atomic<bool>* stop = nullptr;
  };
  ErptChains(const Tracer& tracer, const Config& config, Film& film, ErptStats& stats, StageTimes& times);

  // Starts floor(U + e / (m e_d)) chains for each seed of the batch (detailed balance: one,
  // depositing e / m per step; at most Config::maxChainsPerSeed, each then depositing
  // e / (m cap)) and runs steps whenever the queue is full; on return every chain of the batch
  // is in the queue (or done). Seeds no chain can move (InPlaceReason), and every seed when
  // e_d = 0, are deposited at their own film position. False: stopped (Config::stop).
  bool consume(const SeedStore& batch);
  // Runs the remaining chains to the end. False: stopped (Config::stop).
  bool finish();
  // The machine's state between batches with no chain in flight (after finish()): random
  // stream counters, deposit totals, tally, filter counts. load() also empties the queue.
  void save(ByteWriter& w) const;
  void load(ByteReader& r);
  // Split renders: the proposal tally becomes its total over the processes (`sum` adds doubles).
  template <class Sum>
  void reduceTally(const Sum& sum) { erpt::reduceTally(tally_, sum); }
  // Energy added to the film so far (luminance), for tests.
  double depositedEnergy() const { return deposited_; }
  // The part of it deposited by seeds in place (InPlaceReason).
  double inPlaceEnergy() const { return inPlaceDeposited_; }
  // Complete proposals per pixel (when Config::tallyProposals).
  const std::vector<uint32_t>& proposalTally() const { return tally_; }

 private:
  const ErptSettings& settings() const { return config_.step.settings; }
  bool refill();  // true when every slot is busy afterwards
  void step();
  // Deposits `energy` (luminance) in the seed's colour at its film position, counted by `why`.
  void depositInPlace(const SeedStore& store, size_t seed, double energy, InPlaceReason why);
  bool anyActive() const;
  bool stopped() const;

  const Tracer& tracer_;
  Config config_;
  Film& film_;
  ErptStats& stats_;
  StageTimes& times_;
  ErptQueues q_;
  ErptCounters counters_;
  // Chains of the current batch waiting for a slot.
  struct PendingSeed {
    uint32_t seed, copiesLeft;
    float energyPerStep;  // luminance each step of these chains deposits
  };
  const SeedStore* batch_ = nullptr;
  std::vector<PendingSeed> pending_;
  std::vector<uint8_t> zeroF_;  // per seed starting chains: seedHasZeroContribution()
  size_t pendingNext_ = 0;
  uint64_t seedCounter_ = 0, chainCounter_ = 0;
  double deposited_ = 0, inPlaceDeposited_ = 0;
  std::vector<uint32_t> tally_;
  DepositFilters filters_;
};

}  // namespace erpt
