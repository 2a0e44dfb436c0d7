#include "integrators/pmc_er/pmc_population.h"

#include <chrono>
#include <cmath>
#include <optional>

#include "core/parallel.h"
#include "stages/chain_step.h"
#include "integrators/systematic_resampling.h"
#include "core/rng.h"
#include "integrators/seed_checks.h"
#include "integrators/seed_sampler.h"
#include "integrators/path/path_integrator.h"
#include "sample_passes.h"

namespace erpt {

namespace {
constexpr size_t kGrain = 256;
constexpr uint64_t kMemberStream = 0x6d656d626572ull, kPickStream = 0x7069636bull, kCombStream = 0x636f6d62ull,
                   kRunStream = 0x72756eull;

double secondsSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// Iterations after the pool is used up: until a member holds at most `remainder` of what it
// had, depositing `share` of what it holds per iteration.
int drainIterations(double share, double remainder) {
  if (share >= 1 || remainder >= 1) return 0;
  return int(std::ceil(std::log(remainder) / std::log(1 - share)));
}
}  // namespace

size_t PmcPopulation::bytesPerMember(int components) {
  // The queues, the spare chain row and path for resampling, energy, alpha sums and weights;
  // about as much again for the candidates' seed copies and the pool's path-tracer batch.
  const size_t member = StepQueues::bytesPerSlot() + sizeof(ChainQueue::Row) + kMaxChainVertices * sizeof(VertexQueue::Row) +
                        sizeof(double) + size_t(components) * (sizeof(double) + sizeof(float));
  return 2 * member;
}

PmcPopulation::PmcPopulation(const RenderSetup& tracing, const Config& config, PmcMixture& mixture, RenderStats& stats)
    : tracing_(tracing),
      config_(config),
      mixture_(mixture),
      stats_(stats),
      pmc_(pmcStatsOf(stats)),
      slotCount_(size_t(std::max(1, config.pmc.population))),
      components_(mixture.components()) {
  const size_t n = slots(), k = size_t(components_);
  energy_.assign(n, 0.0);
  alphaSum_.assign(n * k, 0.0);
  alpha_.assign(n * k, 1.0f / float(k));
  if (mixture_.adapt() == PmcAdapt::Member) mixture_.setMemberWeights(alpha_.data());
  regionSums_.assign(size_t(mixture_.regionCount()) * k, 0.0);
  const size_t pixels = size_t(tracing.film.width()) * size_t(tracing.film.height());
  stratCount_.assign(pixels, 0.0);
  stratRadius_.assign(pixels, 0.0);
  stratAccept_.assign(pixels, 0.0);
  filters_.maxConsecutive = uint32_t(config.chains.maxConsecutive);
  tallies_.allocate(pixels, config.chains.pmFilterRadius >= 0, config.chains.chainMaps);
  tallies_.attach(filters_);
  for (size_t first = 0; first < n; first += kPmcLaneSlots) {
    const size_t rows = std::min(kPmcLaneSlots, n - first);
    lanes_.push_back(std::make_unique<ChainLane>(rows));
    lanes_.back()->filters.maxConsecutive = filters_.maxConsecutive;
    tallies_.attach(lanes_.back()->filters);
    spareChains_.emplace_back().resize(rows);
    spareVertices_.emplace_back().resize(rows * kMaxChainVertices);
  }
  records_.resize(lanes_.size());
  pmc_.population = n;
  pmc_.radiusCount = components_;
  for (int i = 0; i < components_; ++i) pmc_.radii[i] = mixture.radii()[size_t(i)];
}

bool PmcPopulation::run(const PoolRounds& rounds, int maxIterations, const std::function<void(double)>& progress,
                        const std::atomic<bool>* stop, const std::function<size_t(size_t)>& allowed) {
  const PmcSettings& s = config_.pmc;
  // Each run its own member streams and combs; a pick is keyed by its position in the whole
  // pool, unique over runs and ranks. (The first run of a render keeps the render's seed.)
  runSeed_ = rounds.first == 0 ? config_.seed : streamKey(config_.seed, kRunStream, rounds.first);
  chainCounter_ = 0;
  poolCursor_ = 0;
  std::fill(energy_.begin(), energy_.end(), 0.0);  // after a stopped run, what it held is dropped
  candidates_.clear();
  candidateEnergy_.clear();
  const size_t perIteration = std::max<size_t>(1, size_t(std::llround(s.resampleRate * double(slots()))));
  const int drain = drainIterations(s.resampleRate, s.drainRemainder);
  regenerate(rounds, std::min(slots(), rounds.size()));
  resample(0, slots());
  large_.clear();
  exact_.reset();
  if (config_.film) {
    // After the first resampling every member holds the same energy: its deposit per step
    // sets the unit of this run's exact film.
    const double perStep = energy_.empty() ? 0.0 : energy_[0] * s.resampleRate / s.mutationsPerMember;
    const int w = config_.film->width(), h = config_.film->height();
    exact_ = std::make_unique<ExactFilm>(w, h, exactFilmUnit(perStep), !LaneFilms::fit(lanes_.size(), w, h));
    laneFilms_.reset(lanes_.size(), w, h, exactFilmUnit(perStep));
  }
  int drained = 0;
  size_t members = slots();
  bool taking = true;
  for (uint64_t it = 1;; ++it) {
    if (stopRequested(stop)) {
      // Every member deposits what it holds where it stands, so the film holds the energy of
      // the positions taken (the render keeps it or rolls back: RenderStats::keptSpp).
      settleFilm();
      return false;
    }
    const bool last = maxIterations >= 0 && it >= uint64_t(maxIterations);
    size_t take = 0;
    if (!last) {
      // Asked before the iteration, whose steps the next candidates' path tracing then runs
      // beside (it does not depend on them).
      const size_t cap = allowed ? std::min(rounds.size(), allowed(poolCursor_)) : rounds.size();
      taking = taking && poolCursor_ < cap;
      // An iteration never takes positions of two rounds, so that the population stands
      // between rounds at every round's end (where a time budget may stop it), in every run.
      const size_t roundEnd = (poolCursor_ / rounds.pool.pixels + 1) * size_t(rounds.pool.pixels);
      if (taking) take = std::min({perIteration, cap - poolCursor_, roundEnd - poolCursor_});
    }
    iterate(take > 0 ? std::function<void()>([&] { regenerate(rounds, take); }) : std::function<void()>());
    if (last) break;
    if (take == 0) {
      if (drained++ >= drain) break;
      // Draining: no new members, so the population shrinks with its energy (each member
      // keeps about the energy it had, and the work per iteration falls by 1 - r).
      ++pmc_.drainIterations;
      members = std::max<size_t>(1, size_t(std::ceil(double(members) * (1 - s.resampleRate))));
    }
    resample(it, members);
    if (progress) progress(double(poolCursor_) / double(std::max<size_t>(1, rounds.size())));
  }
  pmc_.poolSize += allowed ? poolCursor_ : rounds.size();  // an open-ended pool: what was taken
  settleFilm();
  pmc_.meanDeposit = depositSteps_ > 0 ? depositSum_ / double(depositSteps_) : 0;
  if (config_.film) pmc_.steps = depositSteps_;
  for (int k = 0; k < kMutationKindCount; ++k) {
    chainStatsOf(stats_).proposed[k] = counters_.proposed[k];
    chainStatsOf(stats_).accepted[k] = counters_.accepted[k];
  }
  for (int r = 0; r < kRejectReasonCount; ++r) chainStatsOf(stats_).rejected[r] = counters_.rejected[r];
  chainStatsOf(stats_).discardedDeposits = filters_.discarded;
  chainStatsOf(stats_).discardedEnergy = filters_.discardedEnergy;
  return true;
}

void PmcPopulation::save(ByteWriter& w) const {
  counters_.save(w);
  w.put(filters_.discarded), w.put(filters_.discardedEnergy);
  w.put(deposited_), w.put(depositSum_), w.put(depositSteps_);
  tallies_.save(w);
  w.putVector(stratCount_), w.putVector(stratRadius_), w.putVector(stratAccept_);
}

void PmcPopulation::load(ByteReader& r) {
  counters_.load(r);
  r.get(filters_.discarded), r.get(filters_.discardedEnergy);
  r.get(deposited_), r.get(depositSum_), r.get(depositSteps_);
  tallies_.load(r);
  r.getVector(stratCount_, stratCount_.size());
  r.getVector(stratRadius_, stratRadius_.size());
  r.getVector(stratAccept_, stratAccept_.size());
}

void PmcPopulation::reduce(const std::function<void(std::vector<double>&)>& sum) {
  tallies_.reduce(sum);
  sum(stratCount_), sum(stratRadius_), sum(stratAccept_);
}

void PmcPopulation::regenerate(const PoolRounds& rounds, size_t count) {
  const auto start = std::chrono::steady_clock::now();
  const size_t first = poolCursor_;
  if (!poolScratch_) poolScratch_ = std::make_unique<PathTracerScratch>();
  poolSeeds_.clear();
  PathTraceOutput out;
  out.seeds = &poolSeeds_;
  out.scratch = poolScratch_.get();
  out.seedSink = [&](SeedStore& batch) { absorb(batch, rounds, first); };
  const PathSampleSet samples{count, [&](size_t k, uint32_t& pixel, uint32_t& sample) { rounds.at(first + k, pixel, sample); }};
  RenderStats traced;
  traceSeedSamples(config_.seeds, tracing_.film.height(), tracing_, samples, out, traced);
  poolCursor_ += count;
  pmc_.poolUsed += count;
  stats_.samples += traced.samples;
  stats_.rays += traced.rays;
  stats_.invalidSamples += traced.invalidSamples;
  for (const auto& [name, seconds] : traced.stages.all()) stats_.stages.add("pool " + name, seconds);
  pmc_.regenerateSeconds += secondsSince(start);
}

void PmcPopulation::absorb(SeedStore& batch, const PoolRounds& rounds, size_t first) {
  const StepConfig& ctx = config_.step;
  const bool excludeDirect = config_.chains.directSamples > 0;
  // One candidate per pool position: of its seeds that a chain can hold, one chosen with
  // probability proportional to its energy, carrying their total energy (unbiased: the
  // expected deposit of each seed is its own X_f). Seeds no mutation can move go where they are.
  std::vector<double> total, cumulative;
  std::vector<int64_t> chosen, lastEligible;
  std::vector<float> energy(batch.size(), 0.0f);
  auto grow = [&](uint32_t path) {
    if (path >= total.size()) {
      total.resize(path + 1, 0.0);
      cumulative.resize(path + 1, 0.0);
      chosen.resize(path + 1, -1);
      lastEligible.resize(path + 1, -1);
    }
  };
  for (size_t i = 0; i < batch.size(); ++i) {
    if (!seedForChains(batch, i, excludeDirect)) continue;
    const float e = luminance(batch.contribution(i));
    if (!(e > 0) || !std::isfinite(e)) continue;
    pmc_.poolEnergy += e;
    foldSeedTail(ctx, batch, i);
    if (const InPlaceReason why = seedSignatureReason(ctx, batch, i); why != kInPlaceReasonCount) {
      ++pmc_.inPlaceSeeds;
      ++chainStatsOf(stats_).inPlace[why];
      if (config_.film) deposited_ += depositSeedInPlace(ctx.measure.film, batch, i, e, *config_.film);
      continue;
    }
    energy[i] = e;
    grow(batch.seeds.path[i]);
    total[batch.seeds.path[i]] += e;
  }
  for (size_t i = 0; i < batch.size(); ++i) {
    if (!(energy[i] > 0)) continue;
    const uint32_t p = batch.seeds.path[i];
    const double u = uniformDouble(streamKey(config_.seed, kPickStream, rounds.index(first + p)), 0) * total[p];
    cumulative[p] += energy[i];
    lastEligible[p] = int64_t(i);
    if (chosen[p] < 0 && cumulative[p] > u) chosen[p] = int64_t(i);
  }
  std::vector<uint32_t> picks;  // (seed), in path order
  std::vector<double> pickEnergy;
  for (size_t p = 0; p < total.size(); ++p) {
    if (!(total[p] > 0)) continue;
    picks.push_back(uint32_t(chosen[p] >= 0 ? chosen[p] : lastEligible[p]));  // rounding guard
    pickEnergy.push_back(total[p]);
  }
  std::vector<uint8_t> zero(picks.size(), 0);
  forEachRange("pmc seed check", picks.size(), 64, [&](IndexRange r) {
    for (size_t k = r.begin; k < r.end; ++k) zero[k] = seedHasZeroContribution(ctx, batch, picks[k]);
  }, &stats_.stages);
  for (size_t k = 0; k < picks.size(); ++k) {
    if (zero[k]) {
      ++pmc_.inPlaceSeeds;
      ++chainStatsOf(stats_).inPlace[kInPlaceZeroContribution];
      if (config_.film) deposited_ += depositSeedInPlace(ctx.measure.film, batch, picks[k], pickEnergy[k], *config_.film);
      continue;
    }
    candidates_.append(batch, picks[k]);
    candidateEnergy_.push_back(pickEnergy[k]);
    ++pmc_.candidates;
  }
}

void PmcPopulation::resample(uint64_t iteration, size_t members) {
  const auto start = std::chrono::steady_clock::now();
  const size_t n = slots(), k = size_t(components_);
  members = std::min(members, n);
  std::vector<double> weights(energy_);
  weights.insert(weights.end(), candidateEnergy_.begin(), candidateEnergy_.end());
  double total = 0;
  for (double w : weights) total += w;
  const double u = uniformDouble(streamKey(runSeed_, kCombStream, iteration), 0);
  const std::vector<uint32_t> counts = systematicCounts(weights, members, u);
  const double tau = total / double(members);
  std::vector<double> energy(n, 0.0), alphaSum(n * k, 0.0);
  // Where each item's copies go and the number of the first new random stream it takes, in
  // the order of one pass over the members then the candidates (so the copying below may run
  // in any order: each target slot is written once).
  const size_t items = counts.size();
  std::vector<size_t> firstSlot(items + 1, 0);
  std::vector<uint64_t> firstStream(items, 0);
  uint64_t streams = chainCounter_;
  for (size_t i = 0; i < items; ++i) {
    firstSlot[i + 1] = firstSlot[i] + counts[i];
    firstStream[i] = streams;
    // A member's first copy keeps its stream; its other copies and every copy of a candidate
    // move on with streams of their own.
    streams += i < n ? (counts[i] > 0 ? counts[i] - 1 : 0) : counts[i];
    if (i < n) {
      if (energy_[i] > 0 && counts[i] == 0) {
        ++pmc_.eliminated;
        pmc_.energyEliminated += energy_[i];
      }
      pmc_.split += counts[i] > 1 ? counts[i] - 1 : 0;
    } else {
      pmc_.energyRegenerated += candidateEnergy_[i - n];
      pmc_.membersBorn += counts[i] > 0;
      pmc_.split += counts[i] > 1 ? counts[i] - 1 : 0;
    }
  }
  chainCounter_ = streams;
  forEachRange("pmc resample", items, 64, [&](IndexRange r) {
    for (size_t i = r.begin; i < r.end; ++i)
      for (uint32_t c = 0; c < counts[i]; ++c) {
        const size_t slot = firstSlot[i] + c;
        ChainQueue& to = spareChains_[slot / kPmcLaneSlots];
        VertexQueue& toVertices = spareVertices_[slot / kPmcLaneSlots];
        const size_t toRow = rowOf(slot);
        energy[slot] = tau;
        if (i >= n) {  // a candidate: new members start with uniform alpha (zero sums)
          loadChainFromSeed(to, toVertices, toRow, candidates_, i - n,
                            streamKey(runSeed_, kMemberStream, firstStream[i] + c), 0, 0);
          continue;
        }
        const ChainLane& from = laneOf(i);
        const size_t row = rowOf(i);
        to.copyRow(toRow, from.q.chains, row);
        for (size_t j = 0; j < from.q.chains.vertexCount[row]; ++j)
          toVertices.copyRow(toRow * kMaxChainVertices + j, from.q.chainVertices, row * kMaxChainVertices + j);
        if (c > 0) {
          to.key[toRow] = streamKey(runSeed_, kMemberStream, firstStream[i] + c - 1);
          to.step[toRow] = 0;
        }
        for (size_t j = 0; j < k; ++j) alphaSum[slot * k + j] = alphaSum_[i * k + j];
      }
  }, &stats_.stages);
  size_t slot = firstSlot[items];
  for (; slot < n; ++slot) spareChains_[slot / kPmcLaneSlots].stepsLeft[rowOf(slot)] = 0;  // only when nothing has energy
  for (size_t l = 0; l < lanes_.size(); ++l) {
    std::swap(lanes_[l]->q.chains, spareChains_[l]);
    std::swap(lanes_[l]->q.chainVertices, spareVertices_[l]);
  }
  energy_.swap(energy);
  alphaSum_.swap(alphaSum);
  candidates_.clear();
  candidateEnergy_.clear();
  pmc_.resampleSeconds += secondsSince(start);
}

void PmcPopulation::iterate(const std::function<void()>& alongside) {
  const auto start = std::chrono::steady_clock::now();
  const size_t n = slots(), k = size_t(components_);
  const PmcSettings& s = config_.pmc;
  const int steps = s.mutationsPerMember;
  if (mixture_.adapt() == PmcAdapt::Member) {
    // The paper's adaptation: the member's accumulated acceptances per radius.
    for (size_t i = 0; i < n; ++i) alphaFromAcceptance(&alphaSum_[i * k], components_, s.alphaFloor, &alpha_[i * k]);
    for (size_t i = 0; i < n; ++i)
      if (energy_[i] > 0) {
        const float* a = &alpha_[i * k];
        for (size_t j = 0; j < k; ++j) ++pmc_.alphaHistogram[j][std::min(kAlphaBins - 1, int(a[j] * kAlphaBins))];
      }
  }
  for (size_t i = 0; i < n; ++i) {
    const bool member = energy_[i] > 0;
    ChainQueue& chains = laneOf(i).q.chains;
    chains.stepsLeft[rowOf(i)] = member ? uint32_t(steps) : 0;
    chains.energy[rowOf(i)] = member ? float(energy_[i] * s.resampleRate / steps) : 0.0f;
  }
  // Task 0 is `alongside` (when given), the others the lanes: they share no data (the
  // candidates' path tracing writes the film's in-place seeds and the candidates, the lanes
  // their queues and the exact film).
  const size_t extra = alongside ? 1 : 0;
  forEachRange("pmc lanes", lanes_.size() + extra, 1, [&](IndexRange r) {
    for (size_t t = r.begin; t < r.end; ++t)
      if (t < extra) alongside();
      else runLane(t - extra, steps);
  });
  // In lane order, so that the sums below are the same for any thread count.
  ChainLane::Totals totals;
  // Lane thread-seconds over the threads that ran them: about the wall time of each stage.
  const double threads = double(std::max<size_t>(1, std::min(lanes_.size(), workerSlots())));
  for (auto& lane : lanes_) lane->takeTotals(totals, stats_.stages, 1.0 / threads, large_);
  chainStatsOf(stats_).rays += totals.rays;
  stats_.rays += totals.rays;
  deposited_ += totals.deposited;
  filters_.discarded += totals.discarded;
  filters_.discardedEnergy += totals.discardedEnergy;
  ChainStats& chainStats = chainStatsOf(stats_);
  for (size_t l = 0; l < lanes_.size(); ++l)
    for (const StepRecord& r : records_[l]) collect(l * kPmcLaneSlots + r.row, r, chainStats);
  tallyStrategies();
  for (size_t i = 0; i < n; ++i) energy_[i] *= 1 - s.resampleRate;
  ++(config_.film ? pmc_.iterations : pmc_.trainingIterations);
  (config_.film ? pmc_.chainSeconds : pmc_.trainSeconds) += secondsSince(start);
}

void PmcPopulation::runLane(size_t l, int steps) {
  ChainLane& lane = *lanes_[l];
  const size_t rows = lane.q.chains.size(), first = l * kPmcLaneSlots, k = size_t(components_);
  // The lane's view of the kernel: member weights are rows of alpha_ from the lane's first
  // slot (a copy of the mixture pointing there); the other modes share the mixture.
  std::optional<PmcMixture> memberKernel;
  if (mixture_.adapt() == PmcAdapt::Member) {
    memberKernel.emplace(mixture_);
    memberKernel->setMemberWeights(&alpha_[first * k]);
  }
  const ProposalPolicy* kernel = memberKernel ? &*memberKernel : &mixture_;
  std::vector<StepRecord>& records = records_[l];
  records.clear();
  std::vector<float> fromX(rows), fromY(rows);
  for (int t = 0; t < steps; ++t) {
    // Where each member stands before the step (its proposal's y).
    std::copy(lane.q.chains.filmX.begin(), lane.q.chains.filmX.begin() + ptrdiff_t(rows), fromX.begin());
    std::copy(lane.q.chains.filmY.begin(), lane.q.chains.filmY.begin() + ptrdiff_t(rows), fromY.begin());
    lane.step(tracing_.tracer, config_.step, kernel, counters_, exact_ ? &laneFilms_.of(l, *exact_) : nullptr);
    const ProposalQueue& p = lane.q.proposals;
    for (size_t row = 0; row < rows; ++row) {
      if (!(energy_[first + row] > 0)) continue;
      const float q = p.acceptance[row];
      records.push_back(StepRecord{uint32_t(row), p.mutation[row], uint8_t(p.component[row]),
                                   uint8_t(q > 0 && p.reason[row] != kRejectByChance), q, fromX[row], fromY[row],
                                   lane.q.chains.energy[row]});
    }
  }
}

void PmcPopulation::collect(size_t slot, const StepRecord& r, ChainStats& chainStats) {
  const size_t k = size_t(components_);
  ++chainStats.mutations;
  ++chainStats.deposits;
  depositSum_ += r.energy;
  ++depositSteps_;
  if (r.kind == uint8_t(MutationKind::None)) return;
  const size_t c = r.component;
  ++pmc_.proposed[c][r.kind];
  pmc_.accepted[c][r.kind] += r.accepted;
  pmc_.acceptanceSum[c][r.kind] += r.acceptance;
  if (mixture_.adapt() == PmcAdapt::Member) alphaSum_[slot * k + c] += r.acceptance;
  if (!config_.film) regionSums_[size_t(mixture_.regionOf(r.fromX, r.fromY)) * k + c] += r.acceptance;
}

void PmcPopulation::tallyStrategies() {
  const int w = tracing_.film.width(), h = tracing_.film.height();
  const std::vector<float>& radii = mixture_.radii();
  // About four bands per run, whatever the image's height.
  const size_t grain = std::max<size_t>(1, size_t(h) / 4);
  forEachRange("pmc strategy tally", size_t(h), grain, [&](IndexRange band) {
    for (const std::vector<StepRecord>& records : records_)
      for (const StepRecord& r : records) {
        if (r.kind == uint8_t(MutationKind::None)) continue;
        const int px = int(std::floor(r.fromX)), py = int(std::floor(r.fromY));
        if (px < 0 || px >= w || py < int(band.begin) || py >= int(band.end)) continue;
        const size_t pixel = size_t(py) * size_t(w) + size_t(px);
        stratCount_[pixel] += 1;
        stratRadius_[pixel] += radii[r.component];
        stratAccept_[pixel] += r.acceptance;
      }
  }, &stats_.stages);
}

void PmcPopulation::settleFilm() {
  if (!config_.film) return;
  depositRemaining();
  addLargeDeposits(large_, config_.step.measure.film, *config_.film);
  laneFilms_.mergeInto(*exact_, &stats_.stages);
  exact_->moveInto(*config_.film);
}

void PmcPopulation::depositRemaining() {
  for (size_t i = 0; i < slots(); ++i) {
    if (!(energy_[i] > 0)) continue;
    const ChainQueue& chains = laneOf(i).q.chains;
    const Color d = chains.colorAt(rowOf(i)) * float(energy_[i]);
    config_.step.measure.film.splat(chains.filmX[rowOf(i)], chains.filmY[rowOf(i)],
                                    [&](uint32_t pixel, float wgt) { config_.film->add(pixel, d * wgt); });
    pmc_.energyFinal += luminance(d);
    deposited_ += luminance(d);
    energy_[i] = 0;
  }
}

RgbImage PmcPopulation::snapshot(double samplesPerPixel) const {
  Film film = *config_.film;
  if (exact_) {
    ExactFilm exact = *exact_;
    LaneFilms lanes = laneFilms_;
    lanes.mergeInto(exact, nullptr);
    exact.moveInto(film);
  }
  std::vector<LargeDeposit> large = large_;
  addLargeDeposits(large, config_.step.measure.film, film);
  for (size_t i = 0; i < slots(); ++i) {
    if (!(energy_[i] > 0)) continue;
    const ChainQueue& chains = laneOf(i).q.chains;
    const Color d = chains.colorAt(rowOf(i)) * float(energy_[i]);
    config_.step.measure.film.splat(chains.filmX[rowOf(i)], chains.filmY[rowOf(i)],
                                    [&](uint32_t pixel, float w) { film.add(pixel, d * w); });
  }
  return film.resolve(samplesPerPixel);
}

RgbImage PmcPopulation::strategyImage() const {
  RgbImage img;
  img.width = tracing_.film.width();
  img.height = tracing_.film.height();
  img.pixels.resize(stratCount_.size());
  for (size_t p = 0; p < stratCount_.size(); ++p) {
    const double c = stratCount_[p];
    img.pixels[p] = c > 0 ? Color(float(c), float(stratRadius_[p] / c), float(stratAccept_[p] / c)) : Color(0.0f);
  }
  return img;
}

}  // namespace erpt
