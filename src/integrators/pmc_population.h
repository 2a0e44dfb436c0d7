// PMC-ER's population machine (docs/pmc-er.md): a fixed number of members in the chain SoA
// queues, driven by the shared chain step a whole iteration at a time. One iteration:
//   every member makes N mutations from its kernel (PmcMixture) and deposits a share r of
//   its energy (r = --resample-rate) spread equally over them (equal deposition: at its
//   current path; balance: detailed-balance deposits at y and the proposals);
//   the next r * population positions of the stratified pool are traced by the wavefront path
//   tracer (one batch) and become candidates;
//   members and candidates are resampled by energy into the slots (pmc_resampling.h).
// When the pool is used up the population drains for a few iterations without new members
// (resampled into fewer slots each time, as its energy falls), then every member deposits
// what it still holds where it stands.
#pragma once

#include <functional>
#include <vector>

#include "erpt/erpt_stages.h"
#include "erpt/pmc_mixture.h"
#include "erpt/pmc_settings.h"
#include "erpt/render.h"
#include "erpt/stratified_pool.h"
#include "render_setup.h"

namespace erpt {

class PmcPopulation {
 public:
  struct Config {
    ErptStepContext step;  // measure and the ERPT settings the chain step reads
    PmcSettings pmc;
    uint64_t seed = 0;     // chain streams, candidate choice and the resampling comb
    Film* film = nullptr;  // where deposits go; null: a training population (deposits nothing)
  };
  // `tracing`: the path tracer's setup (its stage context keys and stratifies pool samples).
  PmcPopulation(const RenderSetup& tracing, const Config& config, PmcMixture& mixture, RenderStats& stats);

  // Runs until the pool is used up and the population drained, then deposits what the
  // members still hold where they stand. maxIterations >= 0 (training): stops after that many
  // iterations and deposits nothing at the end.
  void run(const StratifiedPool& pool, int maxIterations = -1, const std::function<void(double)>& progress = {});

  // Acceptance sums per region of the mixture and component (regions x K) of the proposals
  // made from members in the region (the Region table is built from a training run's).
  const std::vector<double>& regionSums() const { return regionSums_; }
  // Per pixel of the members' paths: R deposits made from there, G mean radius chosen, B mean
  // acceptance (the paper's figure 6).
  RgbImage strategyImage() const;
  const std::vector<uint32_t>& proposalTally() const { return tally_; }
  double depositedEnergy() const { return deposited_; }

 private:
  size_t slots() const { return q_.chains.size(); }
  void regenerate(const StratifiedPool& pool, size_t count);
  void absorb(SeedStore& batch, size_t firstPoolIndex);
  // Members and candidates by energy into the first `members` slots (the rest stay free).
  void resample(uint64_t iteration, size_t members);
  void iterate();
  void collect(const std::vector<float>& fromX, const std::vector<float>& fromY);
  void depositRemaining();

  const RenderSetup& tracing_;
  Config config_;
  PmcMixture& mixture_;
  RenderStats& stats_;
  PmcStats& pmc_;
  ErptQueues q_;
  ChainQueue spareChains_;
  VertexQueue spareVertices_;
  ErptCounters counters_;
  DepositFilters filters_;
  size_t poolCursor_ = 0;
  uint64_t chainCounter_ = 0;
  int components_;
  std::vector<double> energy_, alphaSum_;  // per slot; alphaSum_: K per slot
  std::vector<float> alpha_;               // Member adaptation: K per slot
  SeedStore candidates_;
  std::vector<double> candidateEnergy_;
  std::vector<double> regionSums_;
  std::vector<double> stratCount_, stratRadius_, stratAccept_;
  std::vector<uint32_t> tally_;
  double deposited_ = 0, depositSum_ = 0;
  uint64_t depositSteps_ = 0;
};

}  // namespace erpt
