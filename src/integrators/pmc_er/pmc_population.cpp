#include "integrators/pmc_er/pmc_population.h"

#include <chrono>
#include <cmath>

#include "stages/chain_step.h"
#include "integrators/systematic_resampling.h"
#include "core/rng.h"
#include "integrators/seed_checks.h"
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
      q_(size_t(config.pmc.population)),
      components_(mixture.components()) {
  const size_t n = slots(), k = size_t(components_);
  spareChains_.resize(n);
  spareVertices_.resize(n * kMaxChainVertices);
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
  if (config.chains.pmFilterRadius >= 0) {
    tally_.assign(pixels, 0);
    filters_.proposalTally = &tally_;
  }
  pmc_.population = n;
  pmc_.radiusCount = components_;
  for (int i = 0; i < components_; ++i) pmc_.radii[i] = mixture.radii()[size_t(i)];
}

bool PmcPopulation::run(const PoolRounds& rounds, int maxIterations, const std::function<void(double)>& progress,
                        const std::atomic<bool>* stop) {
  const PmcSettings& s = config_.pmc;
  // Each run its own member streams and combs; a pick is keyed by its position in the whole
  // pool, unique over runs and ranks. (The first run of a render keeps the render's seed.)
  runSeed_ = rounds.first == 0 ? config_.seed : streamKey(config_.seed, kRunStream, rounds.first);
  chainCounter_ = 0;
  poolCursor_ = 0;
  std::fill(energy_.begin(), energy_.end(), 0.0);  // after a stopped run, what it held is dropped
  candidates_.clear();
  candidateEnergy_.clear();
  pmc_.poolSize += rounds.size();
  const size_t perIteration = std::max<size_t>(1, size_t(std::llround(s.resampleRate * double(slots()))));
  const int drain = drainIterations(s.resampleRate, s.drainRemainder);
  regenerate(rounds, std::min(slots(), rounds.size()));
  resample(0, slots());
  int drained = 0;
  size_t members = slots();
  for (uint64_t it = 1;; ++it) {
    if (stopRequested(stop)) return false;
    iterate();
    if (maxIterations >= 0 && it >= uint64_t(maxIterations)) break;
    if (poolCursor_ < rounds.size()) {
      regenerate(rounds, std::min(perIteration, rounds.size() - poolCursor_));
    } else if (drained++ >= drain) {
      break;
    } else {
      // Draining: no new members, so the population shrinks with its energy (each member
      // keeps about the energy it had, and the work per iteration falls by 1 - r).
      ++pmc_.drainIterations;
      members = std::max<size_t>(1, size_t(std::ceil(double(members) * (1 - s.resampleRate))));
    }
    resample(it, members);
    if (progress) progress(double(poolCursor_) / double(std::max<size_t>(1, rounds.size())));
  }
  if (config_.film) depositRemaining();
  pmc_.meanDeposit = depositSteps_ > 0 ? depositSum_ / double(depositSteps_) : 0;
  if (config_.film) pmc_.steps = depositSteps_;
  for (int k = 0; k < kMutationKindCount; ++k) {
    erptStatsOf(stats_).proposed[k] = counters_.proposed[k];
    erptStatsOf(stats_).accepted[k] = counters_.accepted[k];
  }
  for (int r = 0; r < kRejectReasonCount; ++r) erptStatsOf(stats_).rejected[r] = counters_.rejected[r];
  erptStatsOf(stats_).discardedDeposits = filters_.discarded;
  erptStatsOf(stats_).discardedEnergy = filters_.discardedEnergy;
  return true;
}

void PmcPopulation::save(ByteWriter& w) const {
  counters_.save(w);
  w.put(filters_.discarded), w.put(filters_.discardedEnergy);
  w.put(deposited_), w.put(depositSum_), w.put(depositSteps_);
  w.putVector(tally_);
  w.putVector(stratCount_), w.putVector(stratRadius_), w.putVector(stratAccept_);
}

void PmcPopulation::load(ByteReader& r) {
  counters_.load(r);
  r.get(filters_.discarded), r.get(filters_.discardedEnergy);
  r.get(deposited_), r.get(depositSum_), r.get(depositSteps_);
  r.getVector(tally_, tally_.size());
  r.getVector(stratCount_, stratCount_.size());
  r.getVector(stratRadius_, stratRadius_.size());
  r.getVector(stratAccept_, stratAccept_.size());
}

void PmcPopulation::reduce(const std::function<void(std::vector<double>&)>& sum) {
  reduceTally(tally_, sum);
  sum(stratCount_), sum(stratRadius_), sum(stratAccept_);
}

void PmcPopulation::regenerate(const PoolRounds& rounds, size_t count) {
  const auto start = std::chrono::steady_clock::now();
  const size_t first = poolCursor_;
  SeedStore store;
  PathTraceOutput out;
  out.seeds = &store;
  out.seedSink = [&](SeedStore& batch) { absorb(batch, rounds, first); };
  const PathSampleSet samples{count, [&](size_t k, uint32_t& pixel, uint32_t& sample) { rounds.at(first + k, pixel, sample); }};
  RenderStats traced;
  tracePathSamples(tracing_, samples, out, traced);
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
    if (seedSignatureReason(ctx, batch, i) != kInPlaceReasonCount) {
      ++pmc_.inPlaceSeeds;
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
  size_t slot = 0;
  for (size_t i = 0; i < n; ++i) {
    if (energy_[i] > 0 && counts[i] == 0) {
      ++pmc_.eliminated;
      pmc_.energyEliminated += energy_[i];
    }
    for (uint32_t c = 0; c < counts[i]; ++c, ++slot) {
      spareChains_.copyRow(slot, q_.chains, i);
      for (size_t j = 0; j < q_.chains.vertexCount[i]; ++j)
        spareVertices_.copyRow(slot * kMaxChainVertices + j, q_.chainVertices, i * kMaxChainVertices + j);
      if (c > 0) {
        // A copy moves on with its own random stream.
        spareChains_.key[slot] = streamKey(runSeed_, kMemberStream, chainCounter_++);
        spareChains_.step[slot] = 0;
        ++pmc_.split;
      }
      for (size_t j = 0; j < k; ++j) alphaSum[slot * k + j] = alphaSum_[i * k + j];
      energy[slot] = tau;
    }
  }
  for (size_t j = 0; j < candidateEnergy_.size(); ++j) {
    pmc_.energyRegenerated += candidateEnergy_[j];
    const uint32_t copies = counts[n + j];
    pmc_.membersBorn += copies > 0;
    pmc_.split += copies > 1 ? copies - 1 : 0;
    for (uint32_t c = 0; c < copies; ++c, ++slot) {
      loadChainFromSeed(spareChains_, spareVertices_, slot, candidates_, j,
                        streamKey(runSeed_, kMemberStream, chainCounter_++), 0, 0);
      energy[slot] = tau;  // new members start with uniform alpha (zero sums)
    }
  }
  for (; slot < n; ++slot) spareChains_.stepsLeft[slot] = 0;  // only when nothing has energy
  std::swap(q_.chains, spareChains_);
  std::swap(q_.chainVertices, spareVertices_);
  energy_.swap(energy);
  alphaSum_.swap(alphaSum);
  candidates_.clear();
  candidateEnergy_.clear();
  pmc_.resampleSeconds += secondsSince(start);
}

void PmcPopulation::iterate() {
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
    q_.chains.stepsLeft[i] = member ? uint32_t(steps) : 0;
    q_.chains.energy[i] = member ? float(energy_[i] * s.resampleRate / steps) : 0.0f;
  }
  const ChainStep chainStep{tracing_.tracer, config_.step, &stats_.stages, kGrain, &mixture_};
  std::vector<float> fromX(n), fromY(n);
  for (int t = 0; t < steps; ++t) {
    // Where each member stands before the step (its proposal's y).
    std::copy(q_.chains.filmX.begin(), q_.chains.filmX.begin() + ptrdiff_t(n), fromX.begin());
    std::copy(q_.chains.filmY.begin(), q_.chains.filmY.begin() + ptrdiff_t(n), fromY.begin());
    const uint64_t rays = chainStep.run(q_, counters_);
    erptStatsOf(stats_).rays += rays;
    stats_.rays += rays;
    if (config_.film) {
      const auto t0 = std::chrono::steady_clock::now();
      deposited_ += applyDeposits(q_.chains, q_.proposals, q_.deposits, IndexRange{0, n}, config_.step.measure.film,
                                  *config_.film, filters_);
      stats_.stages.add("chain deposit", secondsSince(t0));
    }
    collect(fromX, fromY);
  }
  for (size_t i = 0; i < n; ++i) energy_[i] *= 1 - s.resampleRate;
  ++(config_.film ? pmc_.iterations : pmc_.trainingIterations);
  (config_.film ? pmc_.chainSeconds : pmc_.trainSeconds) += secondsSince(start);
}

void PmcPopulation::collect(const std::vector<float>& fromX, const std::vector<float>& fromY) {
  const size_t n = slots(), k = size_t(components_);
  const int w = tracing_.film.width(), h = tracing_.film.height();
  const bool member = mixture_.adapt() == PmcAdapt::Member;
  for (size_t i = 0; i < n; ++i) {
    if (!(energy_[i] > 0)) continue;
    const uint8_t kind = q_.proposals.mutation[i];
    ++erptStatsOf(stats_).mutations;
    ++erptStatsOf(stats_).deposits;
    depositSum_ += q_.chains.energy[i];
    ++depositSteps_;
    if (kind == uint8_t(MutationKind::None)) continue;
    const size_t c = q_.proposals.component[i];
    const float q = q_.proposals.acceptance[i];
    ++pmc_.proposed[c][kind];
    pmc_.accepted[c][kind] += q > 0 && q_.proposals.reason[i] != kRejectByChance;
    pmc_.acceptanceSum[c][kind] += q;
    if (member) alphaSum_[i * k + c] += q;
    if (!config_.film) regionSums_[size_t(mixture_.regionOf(fromX[i], fromY[i])) * k + c] += q;
    const int px = int(std::floor(fromX[i])), py = int(std::floor(fromY[i]));
    if (px >= 0 && py >= 0 && px < w && py < h) {
      const size_t p = size_t(py) * size_t(w) + size_t(px);
      stratCount_[p] += 1;
      stratRadius_[p] += mixture_.radii()[c];
      stratAccept_[p] += q;
    }
  }
}

void PmcPopulation::depositRemaining() {
  for (size_t i = 0; i < slots(); ++i) {
    if (!(energy_[i] > 0)) continue;
    const Color d = q_.chains.colorAt(i) * float(energy_[i]);
    config_.step.measure.film.splat(q_.chains.filmX[i], q_.chains.filmY[i],
                                    [&](uint32_t pixel, float wgt) { config_.film->add(pixel, d * wgt); });
    pmc_.energyFinal += luminance(d);
    deposited_ += luminance(d);
    energy_[i] = 0;
  }
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
