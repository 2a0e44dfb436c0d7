// PMC-ER's population machine (docs/pmc-er.md): a fixed number of members in chain lanes
// (chain_lane.h) of kPmcLaneSlots slots each; an iteration runs every lane's N steps on one
// thread each, each lane depositing into its own ExactFilm (lane_films.h), so the image does
// not depend on the thread count. One iteration:
//   every member makes N mutations from its kernel (PmcMixture) and deposits a share r of
//   its energy (r = --resample-rate) spread equally over them (equal deposition: at its
//   current path; balance: detailed-balance deposits at y and the proposals);
//   the next r * population positions of the stratified pool are traced by the wavefront path
//   tracer (one batch) and become candidates;
//   members and candidates are resampled by energy into the slots (systematic_resampling.h).
// When the positions are used up (or the caller says to take no more: a time budget) the
// population drains for a few iterations without new members (resampled into fewer slots each
// time, as its energy falls), then every member deposits what it still holds where it stands. A render runs the population once per group
// of sample passes (pmc_er_integrator.cpp), so that between groups no member is in flight
// and the state is the film plus the accumulators kept here.
#pragma once

#include <atomic>
#include <functional>
#include <vector>

#include <memory>

#include "integrators/chain_lane.h"
#include "integrators/lane_films.h"
#include "stages/chain_stages.h"
#include "stages/pmc_mixture.h"
#include "erpt/pmc_settings.h"
#include "erpt/render.h"
#include "integrators/chain_settings.h"
#include "integrators/pmc_er/stratified_pool.h"
#include "integrators/path/path_integrator.h"
#include "render_setup.h"

namespace erpt {

// Member slots per lane: fixed (not per thread), so that the order in which the lanes' step
// records are collected, and with it every statistic, is the same for any thread count; 512
// gives the default population of 5000 ten lanes, which two to eight threads share evenly.
constexpr size_t kPmcLaneSlots = 512;

class PmcPopulation {
 public:
  struct Config {
    StepConfig step;
    ChainSettings chains;  // the direct-light split and the deposit filters
    PmcSettings pmc;
    uint64_t seed = 0;     // chain streams, candidate choice and the resampling comb
    Film* film = nullptr;  // where deposits go; null: a training population (deposits nothing)
    SeedSampler seeds = SeedSampler::Path;  // what makes the pool's seeds (`tracing` made for it)
  };
  // Memory one member slot takes (queues, spare copies, energies and mixture weights), for
  // refusing populations that would not fit.
  static size_t bytesPerMember(int components);
  // `tracing`: the seed sampler's setup (its stage context keys and stratifies pool samples).
  PmcPopulation(const RenderSetup& tracing, const Config& config, PmcMixture& mixture, RenderStats& stats);

  // Runs over the positions of `rounds` until they are used up, or until the prefix `allowed`
  // returns (asked after every iteration with the positions taken so far; it may grow but not
  // shrink below what was taken) is taken, and the population drained, then deposits what the
  // members still hold where they stand. maxIterations >= 0
  // (training): stops after that many iterations and deposits nothing at the end. Returns
  // false when `stop` was set before the end (the film and the accumulators then hold part of
  // the run: the caller loads the state it saved before it).
  bool run(const PoolRounds& rounds, int maxIterations = -1, const std::function<void(double)>& progress = {},
           const std::atomic<bool>* stop = nullptr, const std::function<size_t(size_t)>& allowed = {});
  // Positions of the last run's rounds it took (all of them unless `allowed` stopped it).
  size_t positionsTaken() const { return poolCursor_; }
  // During a run (from `allowed`, between iterations): the image as if every member deposited
  // what it holds where it stands now, over `samplesPerPixel`. At a round boundary it is an
  // unbiased image of the rounds so far (the members' energy measure is a multiple of f);
  // nothing of the run changes.
  RgbImage snapshot(double samplesPerPixel) const;

  // Render state between runs: statistics, tally and strategy sums (not the members: there
  // are none between runs).
  void save(ByteWriter& w) const;
  void load(ByteReader& r);
  // Split renders: the tally and the strategy sums become their totals over the processes.
  void reduce(const std::function<void(std::vector<double>&)>& sum);

  // Acceptance sums per region of the mixture and component (regions x K) of the proposals
  // made from members in the region (the Region table is built from a training run's).
  const std::vector<double>& regionSums() const { return regionSums_; }
  // Per pixel of the members' paths: R deposits made from there, G mean radius chosen, B mean
  // acceptance (the paper's figure 6).
  RgbImage strategyImage() const;
  const std::vector<uint32_t>& proposalTally() const { return tallies_.proposals; }
  const ProposalTallies& tallies() const { return tallies_; }
  double depositedEnergy() const { return deposited_; }

 private:
  // Member slot i is row i % kPmcLaneSlots of lane i / kPmcLaneSlots.
  size_t slots() const { return slotCount_; }
  ChainLane& laneOf(size_t slot) const { return *lanes_[slot / kPmcLaneSlots]; }
  static size_t rowOf(size_t slot) { return slot % kPmcLaneSlots; }
  // What collect() needs of one member's step, recorded by its lane's thread.
  struct StepRecord {
    uint32_t row;
    uint8_t kind, component, accepted;
    float acceptance, fromX, fromY, energy;
  };
  void regenerate(const PoolRounds& rounds, size_t count);
  // `first`: the position (in the rounds) of the batch's path 0.
  void absorb(SeedStore& batch, const PoolRounds& rounds, size_t first);
  // Members and candidates by energy into the first `members` slots (the rest stay free).
  void resample(uint64_t iteration, size_t members);
  // `alongside` (when set) runs as one more task beside the lanes.
  void iterate(const std::function<void()>& alongside = {});
  // `steps` steps of every member of lane l, on the calling thread.
  void runLane(size_t l, int steps);
  // One record's counts and sums, in the serial order (their floating-point sums depend on it).
  void collect(size_t slot, const StepRecord& r, ChainStats& chainStats);
  // The records' per-pixel strategy sums (the "strategy" image). Random access to three
  // pixel-sized arrays made this most of the serial time between iterations, so bands of image
  // rows run in parallel: each reads every record in the serial order and adds those in its
  // rows, so that every pixel sums in the same order as one pass would (the same bits for any
  // thread count).
  void tallyStrategies();
  void depositRemaining();
  // The end of a run (or a stop): the members deposit what they hold where they stand, then the
  // large deposits and the run's exact film go to the film (when there is one).
  void settleFilm();

  const RenderSetup& tracing_;
  Config config_;
  PmcMixture& mixture_;
  RenderStats& stats_;
  PmcStats& pmc_;
  size_t slotCount_;
  std::vector<std::unique_ptr<ChainLane>> lanes_;
  std::vector<ChainQueue> spareChains_;  // per lane: resampling writes the next members here
  std::vector<VertexQueue> spareVertices_;
  std::vector<std::vector<StepRecord>> records_;  // per lane, the current iteration's
  // The chains' deposits of the current run: its unit follows the run's first deposit per step
  // (exactFilmUnit); at the end of the run its sums move into the film.
  std::unique_ptr<ExactFilm> exact_;
  LaneFilms laneFilms_;  // the lanes' own films (lane_films.h), added into exact_ when it is read
  std::vector<LargeDeposit> large_;
  StepCounters counters_;
  DepositFilters filters_;  // the lanes' filter counts, merged
  size_t poolCursor_ = 0;      // positions of the current run's rounds traced so far
  uint64_t runSeed_ = 0;       // the current run's member streams and resampling comb
  uint64_t chainCounter_ = 0;  // member streams started in the current run
  int components_;
  std::vector<double> energy_, alphaSum_;  // per slot; alphaSum_: K per slot
  std::vector<float> alpha_;               // Member adaptation: K per slot
  SeedStore candidates_;
  std::vector<double> candidateEnergy_;
  // The pool's samples as traced, and the tracer's working memory: kept from round to round.
  SeedStore poolSeeds_;
  std::unique_ptr<PathTracerScratch> poolScratch_;
  std::vector<double> regionSums_;
  std::vector<double> stratCount_, stratRadius_, stratAccept_;
  ProposalTallies tallies_;
  double deposited_ = 0, depositSum_ = 0;
  uint64_t depositSteps_ = 0;
};

}  // namespace erpt
