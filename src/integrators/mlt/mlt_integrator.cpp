// `--integrator mlt`: Metropolis light transport (Veach and Guibas 1997) over the mutation
// engine ERPT uses, so that a comparison of the two measures the algorithms (docs/mlt.md).
//
//   1. Optional (--direct-samples N): paths of at most one bounce go to the direct-lighting
//      pass, as in ERPT; the chains hold paths of two or more bounces.
//   2. Bootstrap (--bootstrap N samples per pixel; by default sized by the chains' work, at
//      most 100,000 samples as pbrt-v4's; its own random stream): the seed sampler's
//      contributions split into those the chains hold (their domain, mlt_stages.h) and the
//      rest, which are deposited where they are (their own unbiased estimate). The domain's
//      total luminance, divided by the samples per pixel, is b, the image's normalisation.
//   3. Chains (--chains C): start states resampled from the bootstrap's domain contributions in
//      proportion to their luminance (systematic resampling, its own stream; the bootstrap is
//      traced a second time, bit-identically, for the chosen paths' samples only). Each chain runs
//      L = M pixels / C steps (M: --mutations-per-pixel), each step a large step with
//      probability --large-step-prob, else ERPT's lens or caustic perturbation, and deposits
//      b / (C L) as expected values at the current and the proposed path.
//   image = chains + in-place contributions + direct pass. A chain alone is only consistent
//   (it starts from an approximation of its stationary distribution); the render is unbiased
//   in expectation, since b and the start states come from the same bootstrap (docs/mlt.md).
#include "integrators/mlt/mlt_integrator.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

#include "integrators/chain_lanes.h"
#include "integrators/group_progress.h"
#include "stages/mlt_stages.h"
#include "core/rng.h"
#include "integrators/seed_checks.h"
#include "integrators/seed_sampler.h"
#include "integrators/redistribution_parts.h"
#include "integrators/path/path_integrator.h"
#include "render_setup.h"
#include "integrators/systematic_resampling.h"
#include "sample_passes.h"
#include "chain_options.h"
#include "integrator_stats.h"

namespace erpt {

namespace {
constexpr uint64_t kBootstrapStream = 0x626f6f74ull, kResampleStream = 0x726573616d70ull,
                   kLargeStepStream = 0x6c61726765ull;

double secondsSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// MLT's choices in every step: the large-step coin (mltChooser), and the large steps of a chain
// lane: the path tracer, run on the lane's thread over one sample per large step, then
// stageMltLargeSteps. The samples run in groups by the vertex count
// their chain asks for, each group's walks stopped at that length (max depth n - 1): the
// path tracer's decisions up to a path's last vertex do not depend on how far it may go on,
// so the candidate is the same as a full walk's, at a fraction of the rays.
class MltPolicy final : public ProposalPolicy {
 public:
  MltPolicy(const Tracer& tracer, const StageContext& ctx, uint32_t pixels)
      : tracer_(tracer), ctx_(ctx), pixels_(pixels) {}

  void choose(const StepConfig& ctx, const ChainQueue& chains, ProposalQueue& proposals, RayQueue& rays,
              IndexRange range) const override {
    mltChooser().choose(ctx, chains, proposals, rays, range);
  }

  uint64_t startOwnProposals(const StepConfig& ctx, StepQueues& q, StageTimes* times) const override {
    const auto start = std::chrono::steady_clock::now();
    Scratch& s = scratch_.local();
    s.slots.clear();
    for (size_t i = 0; i < q.chains.size(); ++i)
      if (q.proposals.state[i] == kProposalLarge) s.slots.push_back(uint32_t(i));
    if (s.slots.empty()) return 0;
    // Slots by the vertex count their chain asks for (a counting sort, slot order kept).
    std::vector<size_t> firstOf(kMaxChainVertices + 2, 0);
    s.vertices.resize(s.slots.size());
    for (size_t k = 0; k < s.slots.size(); ++k) {
      bool nee;
      largeStepTarget(*ctx.largeSteps, q.chains, s.slots[k], s.vertices[k], nee);
      ++firstOf[size_t(s.vertices[k]) + 1];
    }
    for (size_t n = 1; n < firstOf.size(); ++n) firstOf[n] += firstOf[n - 1];
    s.grouped.resize(s.slots.size());
    std::vector<size_t> next(firstOf.begin(), firstOf.end() - 1);
    for (size_t k = 0; k < s.slots.size(); ++k) s.grouped[next[size_t(s.vertices[k])]++] = s.slots[k];
    uint64_t rays = 0;
    StageTimes pathTimes;
    for (int n = 0; n <= kMaxChainVertices; ++n) {
      const size_t begin = firstOf[size_t(n)], count = firstOf[size_t(n) + 1] - begin;
      if (count == 0) continue;
      const uint32_t* slots = s.grouped.data() + begin;
      s.pixel.resize(count);
      s.sample.resize(count);
      for (size_t k = 0; k < count; ++k) largeStepSample(q.chains, slots[k], pixels_, s.pixel[k], s.sample[k]);
      const PathSampleSet samples{count, [&](size_t k, uint32_t& pixel, uint32_t& sample) {
                                    pixel = s.pixel[k];
                                    sample = s.sample[k];
                                  }};
      StageContext group = ctx_;
      group.maxDepth = ctx_.maxDepth >= 0 ? std::min(ctx_.maxDepth, n - 1) : n - 1;
      s.store.clear();
      rays += traceSeedsInline(tracer_, group, samples, s.store, s.path, pathTimes);
      stageMltLargeSteps(ctx, q.chains, s.store, slots, count, q.proposals, q.proposalVertices);
    }
    if (times) times->add("chain large step", secondsSince(start));
    return rays;
  }

 private:
  struct Scratch {
    PathTracerScratch path;
    SeedStore store;
    std::vector<uint32_t> slots, grouped, pixel, sample;
    std::vector<int> vertices;
  };
  const Tracer& tracer_;
  StageContext ctx_;  // the render's, with the large steps' seed and one stratum per pixel
  uint32_t pixels_;
  mutable PerThread<Scratch> scratch_;
};

// The bootstrap's view of one recorded contribution: whether the chains hold it (its
// luminance then counts towards b) or it is deposited where it is.
struct Bootstrap {
  const StepConfig& ctx;
  bool excludeDirect;
  std::vector<float> energies;               // luminance of the domain contributions, in order
  double energyByLength[kMaxChainVertices + 1] = {}, neeEnergyByLength[kMaxChainVertices + 1] = {};
  double total = 0;                          // sum of energies
  // Calls `domain(batch, i, ordinal)` for every contribution the chains hold, in order, and
  // `outside(batch, i, reason)` for every other one with energy.
  template <class Domain, class Outside>
  void classify(const SeedStore& batch, Domain&& domain, Outside&& outside, size_t& ordinal) const {
    PathVertex path[kMaxChainVertices];
    for (size_t i = 0; i < batch.size(); ++i) {
      if (!seedForChains(batch, i, excludeDirect)) continue;
      const float e = luminance(batch.contribution(i));
      if (!(e > 0) || !std::isfinite(e)) continue;
      const int n = int(batch.seeds.vertexCount[i]);
      float w = 0;
      InPlaceReason why = kInPlaceTooLong;
      if (n <= kMaxChainVertices) {
        for (int j = 0; j < n; ++j) loadPathVertex(batch.vertices, batch.seeds.vertexBegin[i] + size_t(j), path[j]);
        why = mltDomainReason(ctx, path, n, batch.seeds.filmX[i], batch.seeds.filmY[i], w);
      }
      if (w > 0)
        domain(batch, i, ordinal++);
      else
        outside(batch, i, why);
    }
  }
};

}  // namespace

void validateMltSettings(const RenderSettings& s) {
  validateChainOptions(chainOf(s));
  const MltSettings& m = mltOf(s);
  const double mutations = double(chainOf(s).mutationsPerPixel) * double(s.width) * double(s.height);
  // A chain's random dimensions are 32-bit (stepDim): past kMaxChainSteps they would repeat.
  if (mutations / double(m.chains) > double(kMaxChainSteps))
    throw UsageError("--mutations-per-pixel x pixels / --chains gives more than " + std::to_string(kMaxChainSteps) +
                     " steps per chain; raise --chains");
  if (chainOf(s).pmFilterRadius >= 0 || chainOf(s).maxConsecutive > 0)
    throw UsageError("--pm-filter and --max-consecutive are ERPT's noise filters; mlt does not take them");
  if (erptOf(s).flow != FlowRule::EqualDeposition) throw UsageError("--flow is ERPT's; mlt does not take it");
  if (s.share.split()) throw UsageError("mlt does not split a render over processes yet");
  if (s.resume || s.onPasses) throw UsageError("mlt does not write checkpoints or partial images yet");
}

RgbImage renderMlt(const Scene& scene, const RenderSettings& s, RenderStats& stats) {
  validateMltSettings(s);
  MltStats& ms = mltStatsOf(stats);
  const ChainOptions& options = chainOf(s);
  StepSettings step = stepSettingsOf(options);
  step.expectedDeposit = true;  // MLT's expected-value splatting of current and proposed paths
  const RgbImage direct = renderDirectPass(scene, s, stats);

  // With BDPT seeds the chains' film density is uniform (film_density.h), and so are the large
  // steps' camera samples (the setup samples film positions uniformly in the pixel).
  RenderSetup setup(scene, s, seedFilmMode(options));
  FilmDensity density(setup.filter, s.width, s.height, options.seeds == SeedSampler::Bdpt);
  LargeStepModel model;
  model.probability = mltOf(s).largeStepProbability;
  model.minVertices = options.directSamples > 0 ? 4 : 2;
  model.maxVertices = s.maxDepth >= 0 ? std::min(kMaxChainVertices, s.maxDepth + 1) : kMaxChainVertices;
  model.rrDepth = setup.ctx.rrDepth;
  // Uniform lengths until the bootstrap knows better: the domain test only asks whether W > 0.
  const double noEnergy[kMaxChainVertices + 1] = {};
  model.setLengths(noEnergy);
  const StepConfig ctx{MeasureContext{scene, setup.lights, setup.camera, density}, step, &model,
                       VertexRange{model.minVertices, model.maxVertices}};
  auto partial = [&] {
    stats.partial = true;
    stats.spp = 0;
    return RgbImage{s.width, s.height, std::vector<Color>(size_t(s.width) * size_t(s.height), Color(0.0f)), {}};
  };

  // Bootstrap, first trace: b, the energy by length, and the contributions the chains do not
  // hold. Sample k is sample k / P of pixel order[k % P]; each domain contribution is noted
  // by its sample and its (vertex count, technique), which name it within its sample.
  auto bootStart = std::chrono::steady_clock::now();
  Bootstrap boot{ctx, options.directSamples > 0, {}};
  Film inPlace(s.width, s.height);
  RenderSettings bs = subRenderSettings(s);
  bs.spp = bootstrapSamplesPerPixel(mltOf(s), double(s.width) * double(s.height), double(options.mutationsPerPixel),
                                    options.seeds == SeedSampler::Bdpt ? kBdptSampleSteps : kPathSampleSteps);
  bs.seed = streamKey(s.seed, kBootstrapStream, 0);
  bs.tracer = setup.sharedTracer;
  const RenderSetup bootSetup(scene, bs, seedFilmMode(options));
  const size_t pixels = bootSetup.order.size();
  const PathSampleSet all{pixels * size_t(bs.spp), [&](size_t k, uint32_t& pixel, uint32_t& sample) {
                            pixel = bootSetup.order[k % pixels];
                            sample = uint32_t(k / pixels);
                          }};
  struct Origin {
    uint64_t sample;
    uint16_t vertices;
    uint8_t technique;  // the seed's explicitLight
  };
  std::vector<Origin> origins;  // per domain ordinal
  SeedStore store;
  size_t ordinal = 0;
  auto firstSink = [&](SeedStore& batch) {
    boot.classify(
        batch,
        [&](const SeedStore& b, size_t i, size_t) {
          const float e = luminance(b.contribution(i));
          boot.energies.push_back(e);
          boot.energyByLength[b.seeds.vertexCount[i]] += e;
          if (b.seeds.explicitLight[i]) boot.neeEnergyByLength[b.seeds.vertexCount[i]] += e;
          boot.total += e;
          origins.push_back({b.seeds.path[i], uint16_t(b.seeds.vertexCount[i]), b.seeds.explicitLight[i]});
        },
        [&](const SeedStore& b, size_t i, InPlaceReason why) {
          ms.inPlaceEnergy += depositSeedInPlace(density, b, i, luminance(b.contribution(i)), inPlace);
          ++ms.inPlaceSeeds;
          ++chainStatsOf(stats).inPlace[why];
        },
        ordinal);
  };
  // Progress: the bootstrap's samples and the chains' steps, as units of work alike.
  const double mutationsRequested = double(options.mutationsPerPixel) * double(s.width) * double(s.height);
  const double work = double(all.count) + mutationsRequested;
  auto bootProgress = [&](double f) {
    if (s.progress) s.progress(f * double(all.count) / work);
  };
  RenderStats bootStats;
  if (!traceSeedSamples(options.seeds, bs.height, bootSetup, all,
                        PathTraceOutput{nullptr, nullptr, &store, firstSink, bootProgress, s.stop}, bootStats))
    return partial();
  const double spp = double(bs.spp);
  ms.bootstrapSamples = bootStats.samples;
  ms.domainSeeds = boot.energies.size();
  ms.inPlaceEnergy /= spp;
  ms.b = boot.total / spp;
  model.setLengths(boot.energyByLength, boot.neeEnergyByLength);

  // The chains' start states; the second trace runs only the samples that made them (the
  // same paths, bit for bit: a sample's random stream is keyed by its pixel and number).
  const double mutations = mutationsRequested;
  const size_t chains = boot.energies.empty() ? 0 : size_t(std::min<double>(mltOf(s).chains, mutations));
  const uint32_t length = chains ? uint32_t(std::max(1.0, std::round(mutations / double(chains)))) : 0;
  // The chains' starts: systematic resampling of the domain contributions by luminance.
  const std::vector<size_t> chosen =
      systematicPicks(std::vector<double>(boot.energies.begin(), boot.energies.end()), chains,
                      uniformDouble(streamKey(s.seed, kResampleStream, 0), 0));
  SeedStore starts;
  if (chains > 0) {
    std::vector<uint64_t> again;  // the samples to trace again, ascending
    for (size_t c : chosen) again.push_back(origins[c].sample);
    std::sort(again.begin(), again.end());
    again.erase(std::unique(again.begin(), again.end()), again.end());
    const PathSampleSet some{again.size(), [&](size_t j, uint32_t& pixel, uint32_t& sample) { all.at(again[j], pixel, sample); }};
    SeedStore retraced;
    RenderStats secondStats;
    if (!traceSeedSamples(options.seeds, bs.height, bootSetup, some,
                          PathTraceOutput{nullptr, nullptr, &retraced, {}, nullptr, s.stop}, secondStats))
      return partial();
    bootStats.rays += secondStats.rays;
    // Each chosen contribution: its sample's row j in `again`, then its (count, technique): a
    // path-traced sample makes one path per count and technique, a BDPT sample one per count
    // and strategy (its light vertices s, in explicitLight).
    auto name = [](uint64_t j, uint32_t vertices, uint32_t technique) {
      return (j << 24) | (uint64_t(vertices & 0xfff) << 12) | (technique & 0xfff);
    };
    std::unordered_map<uint64_t, size_t> byName;
    for (size_t i = 0; i < retraced.size(); ++i)
      byName.emplace(name(retraced.seeds.path[i], retraced.seeds.vertexCount[i], retraced.seeds.explicitLight[i]), i);
    for (size_t next = 0; next < chosen.size();) {
      size_t copies = 1;
      while (next + copies < chosen.size() && chosen[next + copies] == chosen[next]) ++copies;
      const Origin& o = origins[chosen[next]];
      const uint64_t j = uint64_t(std::lower_bound(again.begin(), again.end(), o.sample) - again.begin());
      const auto it = byName.find(name(j, o.vertices, o.technique));
      if (it == byName.end()) throw std::logic_error("mlt: a bootstrap path did not trace again identically");
      starts.append(retraced, it->second, copies);
      next += copies;
    }
  }
  ms.bootstrapSeconds = secondsSince(bootStart);
  ms.chains = chains;
  ms.chainLength = length;
  ms.energyPerStep = chains ? ms.b / (double(chains) * double(length)) : 0;
  stats.rays += bootStats.rays;
  for (const auto& [name, seconds] : bootStats.stages.all()) stats.stages.add("bootstrap " + name, seconds);

  // The chains.
  ChainSettings chainSettings = chainSettingsOf(options);
  chainSettings.chainLength = int(std::max<uint32_t>(length, 1));
  StageContext largeCtx = setup.ctx;
  largeCtx.seed = streamKey(s.seed, kLargeStepStream, 0);
  largeCtx.spp = 1;
  const MltPolicy policy(setup.tracer, largeCtx, uint32_t(s.width) * uint32_t(s.height));
  const double steps = double(chains) * double(length);
  GroupProgress chainProgress;
  chainProgress.start(
      [&](double f) {
        if (s.progress) s.progress((double(all.count) + f * mutations) / work);
      },
      0, steps);
  chainProgress.seeds(1.0);  // every start state is in: the steps alone may reach 1
  ChainLanes::Config config{ctx, chainSettings, s.seed, kErptLaneSlots, ms.energyPerStep, s.stop,
                            [&](uint64_t taken) { chainProgress.chainSteps(taken); }, setup.pool.threads(), &policy};
  ChainLanes machine(setup.tracer, config, setup.film, chainStatsOf(stats), stats.stages);
  const auto chainStart = std::chrono::steady_clock::now();
  const bool done = chains == 0 || (machine.startChains(starts, float(ms.energyPerStep)) && machine.finish());
  ms.chainSeconds = secondsSince(chainStart);
  chainStatsOf(stats).chainSeconds = ms.chainSeconds;
  chainStatsOf(stats).depositEnergy = ms.energyPerStep;
  stats.rays += chainStatsOf(stats).rays;

  // Stopped in the chains: each chain left its remaining energy where it stood
  // (ChainLanes::depositUnfinished), so the image holds all of b; keptSpp is the share of the
  // steps run, in units of the spp.
  RgbImage image = machine.image(1.0);
  const RgbImage rest = inPlace.resolve(spp);
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    image.pixels[i] += rest.pixels[i];
    if (!direct.pixels.empty()) image.pixels[i] += direct.pixels[i];
  }
  stats.spp = done ? 1 : 0;
  if (!done) {
    stats.partial = true;
    // The image holds all of b at any stop: it stands for the share of the steps run.
    stats.keptSpp = std::max(1e-9, double(s.spp) * double(machine.stepsTaken()) / std::max(1.0, steps));
  }
  stats.samples = bootStats.samples;
  addChainMaps(machine.tallies(), s.width, s.height, stats.extraImages);
  return image;
}

std::vector<OptionSpec> metropolisOptions() {
  return {realOption("large-step-prob",
                     "probability that a chain step is a large step: a fresh sample, independent of the chain's path",
                     0, 1, [](auto& s) -> auto& { return mltOf(s).largeStepProbability; }),
          integerOption("bootstrap",
                        "seed-sampler samples per pixel of the bootstrap that estimates the image's luminance b "
                        "and seeds the chains (0: as many as cost about what the chains do, at most 100,000 samples "
                        "and at least 1 per pixel)",
                        0, 65536, [](auto& s) -> auto& { return mltOf(s).bootstrapSpp; }),
          integerOption("chains",
                        "Markov chains, started by resampling the bootstrap's paths by luminance; each runs "
                        "mutations-per-pixel x pixels / chains steps",
                        1, 100000000, [](auto& s) -> auto& { return mltOf(s).chains; })};
}

IntegratorModule mltModule() {
  IntegratorModule m;
  m.name = "mlt";
  m.description = "Metropolis light transport on ERPT's mutations plus an independent large step (docs/mlt.md)";
  // No sample passes (no checkpoints), its own chain length and expected-value deposits, and
  // a bootstrap instead of ERPT's pilot.
  m.options = {mutationsPerPixelOption(), directSamplesOption(), seedsOption(), bidirectionalMutationOption(),
               manifoldPerturbationOption()};
  addOptions(m.options, metropolisOptions());
  addOptions(m.options, perturbationOptions());
  m.options.push_back(chainMapsOption());
  m.sppOption = "mutations-per-pixel";  // Mitsuba's MLT takes its sampler's sample count as this
  m.validate = [](const RenderSettings& s) {
    // A time-budgeted render checks its own per-pass hook in each pass.
    RenderSettings once = s;
    if (s.timeBudget != 0) once.onPasses = nullptr;
    validateMltSettings(once);
  };
  m.render = renderMlt;
  m.printSummary = printMltSummary;
  m.addStats = [](RenderStats& to, const RenderStats& from) {
    addChainStats(chainStatsOf(to), chainStatsOf(from));  // the chain step's counts
    addMltStats(mltStatsOf(to), mltStatsOf(from));
  };
  m.scaleTimedPass = [](const RenderSettings& s, RenderSettings& pass) {
    // Each pass runs the configured mutations per pixel scaled by its share of the spp.
    chainOf(pass).mutationsPerPixel = std::max(1, int(std::lround(double(chainOf(s).mutationsPerPixel) * pass.spp / s.spp)));
    scaleDirectSamples(s, pass);
  };
  return m;
}

}  // namespace erpt
