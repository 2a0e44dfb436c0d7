// `--integrator erpt`: Energy Redistribution Path Tracing (Cline, Talbot, Egbert 2005,
// figure 7) with the equal deposition flow rule.
//
//   1. Pilot pass: a path tracer with its own random stream estimates e_ave, the mean energy
//      of the seeds per pixel sample; e_d = n e_ave / M (eq. 7). It only sets the run time.
//   2. Optional (--direct-samples N): paths of at most one bounce are left out of the seeds
//      and rendered by the stratified direct-lighting integrator instead (as Mitsuba does).
//   3. Main pass: the wavefront path tracer at n samples per pixel, in sample passes
//      (sample_passes.h), streams its seeds batch by batch into the chain machine
//      (chain_lanes.h), which starts floor(U + e / (m e_d)) chains per seed and runs them,
//      to the end after each group of passes; pixel value = sum of deposits / passes done.
#include "integrators/erpt/erpt_integrator.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/rng.h"
#include "integrators/chain_lanes.h"
#include "integrators/group_progress.h"
#include "integrators/noise_filters.h"
#include "integrators/seed_checks.h"
#include "integrators/seed_sampler.h"
#include "integrators/path/path_integrator.h"
#include "render_setup.h"
#include "chain_options.h"
#include "integrators/redistribution_parts.h"
#include "sample_passes.h"
#include "integrator_stats.h"

namespace erpt {

namespace {
constexpr uint64_t kPilotStream = 0x70696c6f74ull, kRankStream = 0x72616e6bull;
}  // namespace

void validateErptSettings(const RenderSettings& s) {
  // The ranges of single options are their declarations' (erptModule); these are the rules
  // that tie values or options together.
  validateChainOptions(chainOf(s));
  if (chainOf(s).maxConsecutive > 0 && erptOf(s).flow == FlowRule::DetailedBalance)
    throw UsageError("--max-consecutive needs moving chains: it does not apply to --flow detailed-balance");
}

// e_ave: mean energy per pixel sample of the seeds ERPT will redistribute.
double erptPilotEnergy(const Scene& scene, const RenderSettings& s, RenderStats& stats) {
  validateErptSettings(s);
  RenderSettings pilot = subRenderSettings(s);
  pilot.spp = erptOf(s).pilotSpp;
  pilot.seed = streamKey(s.seed, kPilotStream, 0);
  SeedStore store;
  pilot.seeds = &store;
  double energy = 0;
  const bool excludeDirect = chainOf(s).directSamples > 0;
  pilot.seedSink = [&](SeedStore& batch) {
    for (size_t i = 0; i < batch.size(); ++i) {
      if (!seedForChains(batch, i, excludeDirect)) continue;
      const float e = luminance(batch.contribution(i));
      if (e > 0 && std::isfinite(e)) energy += e;
    }
  };
  RenderStats pilotStats;
  renderWithSeedSampler(scene, pilot, pilotStats);
  stats.rays += pilotStats.rays;
  if (s.share.split()) {  // the ranks' pilot passes together (pilotStats.spp is already their total)
    std::vector<double> total{energy};
    s.share.sumAcrossRanks(total);
    energy = total[0];
  }
  // A stopped pilot: the render stops too, before its first pass (renderErpt).
  return energy / (double(s.width) * s.height * std::max(1, pilotStats.spp));
}

RgbImage renderErpt(const Scene& scene, const RenderSettings& s, RenderStats& stats) {
  return renderErptWith(scene, s, stats, ErptEnergies{});
}

RgbImage renderErptWith(const Scene& scene, const RenderSettings& s, RenderStats& stats, const ErptEnergies& known) {
  const ChainOptions& o = chainOf(s);
  validateErptSettings(s);
  ChainStats& es = chainStatsOf(stats);
  RgbImage direct;
  if (!s.resume) {  // else pilot energy, e_d and the direct image come with the state
    es.pilotEnergy = known.pilot >= 0 ? known.pilot : erptPilotEnergy(scene, s, stats);
    es.depositEnergy = known.deposit > 0 ? known.deposit : double(s.spp) * es.pilotEnergy / o.mutationsPerPixel;
    // The direct pass first, so that the image of every completed pass is whole. (A split
    // render runs it even when stopped: its ranks must make the same collective calls.)
    if (!stopRequested(s.stop) || s.share.split()) direct = renderDirectPass(scene, s, stats);
  }

  RenderSetup setup(scene, s, seedFilmMode(o));
  FilmDensity density(setup.filter, s.width, s.height, o.seeds == SeedSampler::Bdpt);
  // The chains' random streams: a rank of a split render has its own (its counters start at 0 too).
  const uint64_t chainSeed = s.share.split() ? streamKey(s.seed, kRankStream, uint64_t(s.share.rank)) : s.seed;
  // The chains hold paths of 4 vertices or more when the direct pass renders the shorter ones.
  const VertexRange lengths{o.directSamples > 0 ? 4 : 2,
                            s.maxDepth >= 0 ? std::min(kMaxChainVertices, s.maxDepth + 1) : kMaxChainVertices};
  GroupProgress progress;
  ChainLanes::Config config{StepConfig{MeasureContext{scene, setup.lights, setup.camera, density}, stepSettingsOf(o, erptOf(s).flow),
                                       nullptr, lengths},
                            chainSettingsOf(o, erptOf(s)), chainSeed, kErptLaneSlots, es.depositEnergy, s.stop,
                            [&](uint64_t steps) { progress.chainSteps(steps); }, setup.pool.threads()};
  ChainLanes chains(setup.tracer, config, setup.film, es, stats.stages);
  if (stopRequested(s.stop) && !s.resume && !s.share.split()) {  // stopped in the pilot or the direct pass
    stats.spp = 0;
    stats.partial = true;
    return redistributionImage(s, chains.image(1.0), RgbImage{}, nullptr, nullptr);
  }

  SeedStore store;
  RenderStats seedStats;
  double inChains = 0;
  auto timed = [&](auto&& fn) {
    const auto t = std::chrono::steady_clock::now();
    const bool done = fn();
    inChains += std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
    return done;
  };
  bool chainsRan = true;
  // Every seed goes to the chain machine, also when e_d = 0 (the pilot found no energy): it
  // then deposits the seeds where they are, so no energy is lost.
  auto sink = [&](SeedStore& batch) { chainsRan = timed([&] { return chains.consume(batch); }) && chainsRan; };
  SamplePassHooks passes;
  passes.save = [&](ByteWriter& w) {
    w.put(es);
    w.put(seedStats.samples), w.put(seedStats.rays), w.put(seedStats.invalidSamples);
    w.putVector(direct.pixels);
    setup.film.save(w);
    chains.save(w);
  };
  passes.load = [&](ByteReader& r) {
    r.get(es);
    r.get(seedStats.samples), r.get(seedStats.rays), r.get(seedStats.invalidSamples);
    const size_t directPixels = o.directSamples > 0 ? size_t(s.width) * size_t(s.height) : 0;
    r.getVector(direct.pixels, directPixels);
    direct.width = directPixels ? s.width : 0, direct.height = directPixels ? s.height : 0;
    setup.film.load(r);
    chains.load(r);
  };
  // Passes [first, end): their seeds stream into the chains, which then run to their end, so
  // that the state after the group holds no chain in flight.
  PathTracerScratch seedScratch;
  const size_t pixels = setup.order.size();
  passes.run = [&](int first, int end, const std::function<void(double)>& report) {
    chainsRan = true;
    // The group's chains take about M pixels (end - first) / spp steps (e_d's definition).
    progress.start(report, chains.stepsTaken(),
                   double(o.mutationsPerPixel) * double(pixels) * double(end - first) / double(std::max(1, s.spp)));
    const PathTraceOutput out{nullptr, nullptr, &store, sink, [&](double f) { progress.seeds(f); }, s.stop,
                              &seedScratch};
    if (!traceSeedSamples(o.seeds, s.height, setup, passSamples(setup.order, first, end, s.share), out, seedStats) ||
        !chainsRan)
      return false;
    return timed([&] { return chains.finish(); });
  };
  passes.reduce = [&](const RenderShare& share) {
    setup.film.reduce(share.sumAcrossRanks);
    chains.reduce(share.sumAcrossRanks);
    sumCounters(share, {&seedStats.samples, &seedStats.rays, &seedStats.invalidSamples, &es.seeds, &es.chains,
                        &es.mutations, &es.deposits, &es.rays, &es.cappedSeeds});
  };
  auto image = [&](int done, std::vector<std::pair<std::string, RgbImage>>* extras) {
    RgbImage shown = redistributionImage(s, chains.image(double(done)), direct,
                                         o.pmFilterRadius >= 0 ? &chains.proposalTally() : nullptr, extras);
    if (extras) addChainMaps(chains.tallies(), s.width, s.height, *extras);
    return shown;
  };
  passes.image = [&](int done) { return image(done, nullptr); };
  // A stop inside a group: the seeds of its first samples went to the chains, which deposited
  // all of their energy (ChainLanes::depositUnfinished). Those samples are the passes'
  // samples in pixel order, so each pixel is normalised by its own count of them.
  RgbImage kept;
  passes.stoppedImage = [&](int done, int end, RenderStats& st) {
    const size_t taken = size_t(std::llround(progress.seedShare() * double(pixels) * double(end - done)));
    std::vector<double> perPixel(pixels, double(done) + double(taken / pixels));
    for (size_t k = 0; k < taken % pixels; ++k) perPixel[setup.order[k]] += 1;
    RgbImage deposits = chains.image(1.0);
    for (size_t i = 0; i < pixels; ++i) deposits.pixels[i] *= perPixel[i] > 0 ? float(1.0 / perPixel[i]) : 0.0f;
    st.keptSpp = double(done) + double(taken) / double(pixels);
    kept = redistributionImage(s, std::move(deposits), direct,
                               o.pmFilterRadius >= 0 ? &chains.proposalTally() : nullptr, &st.extraImages);
    addChainMaps(chains.tallies(), s.width, s.height, st.extraImages);
    return kept;
  };
  renderInSamplePasses(s, pixels, stats, passes);
  es.chainSeconds = inChains;
  stats.samples = seedStats.samples;
  stats.rays += seedStats.rays + es.rays;
  stats.invalidSamples = seedStats.invalidSamples;
  for (const auto& [name, seconds] : seedStats.stages.all()) stats.stages.add("seed " + name, seconds);
  if (stats.keptSpp > 0) return kept;
  if (stats.spp == 0) return passes.image(1);  // stopped before the first pass: black
  return image(stats.spp, &stats.extraImages);
}

IntegratorModule erptModule() {
  IntegratorModule m;
  m.name = "erpt";
  m.description = "energy redistribution path tracing (Cline, Talbot, Egbert 2005)";
  m.samplePasses = true;
  m.options = {mutationsPerPixelOption(),
               integerOption("chain-length", "steps m of every chain (paper: 100-1000)", 1, 1 << 24,
                             [](auto& s) -> auto& { return erptOf(s).chainLength; }),
               integerOption("pilot-spp", "samples per pixel of the pilot pass estimating e_ave", 1, 65536,
                             [](auto& s) -> auto& { return erptOf(s).pilotSpp; }),
               choiceOption<FlowRule>("flow",
                                      "equal-deposition (paper section 3.2) or detailed-balance (section 3.1: each "
                                      "seed is mutated --chain-length times and never moves)",
                                      {{"equal-deposition", FlowRule::EqualDeposition},
                                       {"detailed-balance", FlowRule::DetailedBalance}},
                                      [](auto& s) -> auto& { return erptOf(s).flow; }),
               integerOption("max-chains-per-seed",
                             "at most this many chains per seed; a seed that would start more starts this many, each "
                             "depositing more per step (same total)",
                             1, 1000000, [](auto& s) -> auto& { return erptOf(s).maxChainsPerSeed; }),
               directSamplesOption(), seedsOption(), bidirectionalMutationOption(),
               manifoldPerturbationOption()};
  addOptions(m.options, perturbationOptions());
  addOptions(m.options, depositOptions());
  m.options.push_back(chainMapsOption());
  m.validate = [](const RenderSettings& s) { validateErptSettings(s); };
  m.render = renderErpt;
  m.printSummary = printErptSummary;
  m.addStats = [](RenderStats& to, const RenderStats& from) { addChainStats(chainStatsOf(to), chainStatsOf(from)); };
  m.timedPasses = [](const Scene& scene, const RenderSettings& s, RenderStats& stats) -> PassRenderer {
    // One pilot for all passes (it is independent of every one of them), and e_d from the
    // configured spp, so each pass runs the configured mutations per seed.
    ErptEnergies known;
    known.pilot = erptPilotEnergy(scene, s, stats);
    known.deposit = double(s.spp) * known.pilot / std::max(1, chainOf(s).mutationsPerPixel);
    return [known](const Scene& sc, const RenderSettings& pass, RenderStats& ps) {
      return renderErptWith(sc, pass, ps, known);
    };
  };
  m.scaleTimedPass = scaleDirectSamples;
  m.proposalFiltered = true;
  return m;
}

}  // namespace erpt
