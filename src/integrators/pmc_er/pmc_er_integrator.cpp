// `--integrator pmc-er`: population Monte Carlo energy redistribution (Lai, Fan, Chenney,
// Dyer), made unbiased as docs/pmc-er.md derives.
//
//   1. No pilot pass: E_total, for e_d of eq. 4 (reported only; the flow rule deposits a
//      fixed share of each member's energy per iteration), is the pool's own seed energy.
//   2. Region adaptation only: a training population (own stream, own pool, uniform weights,
//      deposits nothing) learns the table of mixture weights per image region; the table is
//      then frozen, so the main population's kernel is a fixed function of the path.
//   3. The population (pmc_population.h) runs over the stratified pool of the render's
//      width x height x spp positions; pixel value = sum of deposits / spp.
//   4. As ERPT: the direct-lighting pass for one-bounce paths (--direct-samples), filters.
#include "integrators/pmc_er/pmc_er_integrator.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "stages/pmc_mixture.h"
#include "core/rng.h"
#include "integrators/budget_clock.h"
#include "integrators/pmc_er/stratified_pool.h"
#include "integrators/redistribution_parts.h"
#include "integrators/seed_sampler.h"
#include "core/system_memory.h"
#include "integrators/pmc_er/pmc_population.h"
#include "render_setup.h"
#include "sample_passes.h"
#include "chain_options.h"
#include "integrator_stats.h"

namespace erpt {

namespace {
constexpr uint64_t kPoolStream = 0x706f6f6cull, kTrainStream = 0x747261696eull;
}  // namespace

namespace {
// --radii r1,r2,...: the mixture's components in pixels.
OptionSpec radiiOption() {
  OptionSpec o("radii", "perturbation radii of the mixture in pixels, comma separated", OptionKind::List);
  o.set = [](RenderSettings& s, const std::string& text) {
    std::vector<float> radii;
    size_t start = 0;
    while (start <= text.size()) {
      const size_t comma = std::min(text.find(',', start), text.size());
      const std::string item = text.substr(start, comma - start);
      char* end = nullptr;
      const float r = std::strtof(item.c_str(), &end);
      if (item.empty() || *end != '\0') throw UsageError("--radii expects comma-separated numbers, got '" + text + "'");
      radii.push_back(r);
      start = comma + 1;
    }
    pmcOf(s).radii = radii;
  };
  o.get = [](const RenderSettings& s) {
    std::string text;
    for (float r : pmcOf(s).radii) text += (text.empty() ? "" : ",") + formatOptionNumber(r);
    return text;
  };
  return o;
}
std::string regionAdaptationOnly(const RenderSettings& s) {
  return pmcOf(s).adapt == PmcAdapt::Region ? "" : "applies to pmc-er with --pmc-adapt region only";
}
}  // namespace

void validatePmcSettings(const PmcSettings& p, const ChainOptions& e) {
  // The ranges of single options are their declarations' (pmcErModule); these tie values together.
  validateChainOptions(e);
  if (p.radii.empty() || p.radii.size() > size_t(kMaxPmcRadii))
    throw UsageError("--radii takes 1 to " + std::to_string(kMaxPmcRadii) + " radii");
  for (float r : p.radii)
    if (!(r > 0) || !(r <= 1e4f)) throw UsageError("--radii: every radius must be in (0, 10000] pixels");
  if (!(p.alphaFloor * float(p.radii.size()) < 1)) throw UsageError("--alpha-floor must be in [0, 1 / (number of radii))");
  if (e.maxConsecutive > 0 && p.flow == PmcFlow::Balance)
    throw UsageError("--max-consecutive needs moving chains: it does not apply to --pmc-flow balance");
}

namespace {
// Region adaptation: the training population (own seed, own pool) learns the table of
// mixture weights per region; independent of the render, so the frozen table is too.
void trainRegionTable(const Scene& scene, const RenderSettings& s, const StepConfig& ctx, PmcMixture& mixture,
                      RenderStats& stats) {
  const PmcSettings& p = pmcOf(s);
  PmcStats& ps = pmcStatsOf(stats);
  const uint32_t pixels = uint32_t(s.width) * uint32_t(s.height);
  RenderSettings ts = subRenderSettings(s);
  ts.seed = streamKey(s.seed, kTrainStream, 0);
  const double positions = double(p.population) * (1.0 + p.trainIterations * p.resampleRate);
  ts.spp = int(std::clamp(std::ceil(positions / pixels), 1.0, double(1 << 20)));
  RenderSetup trainSetup(scene, ts, seedFilmMode(chainOf(s)));
  PmcSettings tp = p;
  tp.adapt = PmcAdapt::Off;
  PmcMixture uniform(tp, s.width, s.height);
  RenderStats trainStats;
  PmcPopulation trainer(trainSetup, PmcPopulation::Config{ctx, chainSettingsOf(chainOf(s)), tp, ts.seed, nullptr, chainOf(s).seeds}, uniform, trainStats);
  trainer.run(PoolRounds::all(StratifiedPool{pixels, uint32_t(ts.spp), ts.seed}), p.trainIterations);
  mixture.setRegionTable(trainer.regionSums(), 1.0);
  ps.trainingIterations = pmcStatsOf(trainStats).trainingIterations;
  ps.trainSeconds = pmcStatsOf(trainStats).trainSeconds + pmcStatsOf(trainStats).regenerateSeconds + pmcStatsOf(trainStats).resampleSeconds;
  stats.rays += trainStats.rays;
  for (int r = 0; r < mixture.regionCount(); ++r)
    for (int k = 0; k < mixture.components(); ++k)
      ++ps.alphaHistogram[k][std::min(kAlphaBins - 1, int(mixture.regionTable()[size_t(r * mixture.components() + k)] * kAlphaBins))];
}
}  // namespace

StepSettings pmcStepSettings(const RenderSettings& s) {
  // The disk lens and Veach caustic units (sizes from the mixture), the families the path
  // allows (Mixed's), detailed-balance deposits for Balance.
  StepSettings step = stepSettingsOf(chainOf(s));  // the deposit rule
  step.strategy = MutationStrategy::Mixed;
  step.lensShape = LensShape::Disk;
  step.causticAngle = CausticAngle::Veach;
  step.flow = pmcOf(s).flow == PmcFlow::Balance ? FlowRule::DetailedBalance : FlowRule::EqualDeposition;
  return step;
}

namespace {
// The summary's energies, from what the render did.
void summarizeEnergies(RenderStats& stats) {
  ChainStats& es = chainStatsOf(stats);
  PmcStats& ps = pmcStatsOf(stats);
  es.chainSeconds = ps.chainSeconds + ps.resampleSeconds;
  // PMC-ER needs no pilot (its energies come from the pool); e_ave for the statistics is the
  // pool's own mean seed energy, what ERPT's pilot pass estimates.
  es.pilotEnergy = ps.poolUsed > 0 ? ps.poolEnergy / double(ps.poolUsed) : 0;
  // Eq. 4 with the steps the render took (E_total = the pool's seed energy): what each would
  // deposit if all were equal.
  const double steps = double(ps.steps);
  ps.depositEnergy = steps > 0 ? es.pilotEnergy * double(ps.poolUsed) / steps : 0;
  es.depositEnergy = ps.depositEnergy;
}
}  // namespace

int usablePopulation(const RenderSettings& s, size_t availableBytes) {
  const double pool = double(s.width) * double(s.height) * double(std::max(1, s.spp));
  const int population = int(std::min(double(pmcOf(s).population), pool));
  const double bytes = double(population) * double(PmcPopulation::bytesPerMember(int(pmcOf(s).radii.size())));
  if (availableBytes > 0 && bytes > 0.8 * double(availableBytes))
    throw UsageError("--population " + std::to_string(population) + " needs about " + humanBytes(bytes) +
                     " for its members; this machine has " + humanBytes(double(availableBytes)) + " available");
  return population;
}

RgbImage renderPmcEr(const Scene& scene, const RenderSettings& requested, RenderStats& stats) {
  const double start = budgetSeconds(requested);
  validatePmcSettings(pmcOf(requested), chainOf(requested));
  RenderSettings s = requested;
  pmcOf(s).population = usablePopulation(requested, availableMemoryBytes());
  pmcStatsOf(stats).requestedPopulation = uint64_t(pmcOf(requested).population);
  const PmcSettings& p = pmcOf(s);
  ChainStats& es = chainStatsOf(stats);
  PmcStats& ps = pmcStatsOf(stats);

  RenderSetup setup(scene, s, seedFilmMode(chainOf(s)));
  FilmDensity density(setup.filter, s.width, s.height, chainOf(s).seeds == SeedSampler::Bdpt);
  const StepConfig ctx{MeasureContext{scene, setup.lights, setup.camera, density}, pmcStepSettings(s)};
  const uint32_t pixels = uint32_t(s.width) * uint32_t(s.height);
  PmcMixture mixture(p, s.width, s.height);
  if (s.timeBudget > 0) {
    if (p.adapt == PmcAdapt::Region) trainRegionTable(scene, s, ctx, mixture, stats);
    const RgbImage image = renderPmcForTime(scene, s, PmcTimeParts{setup, ctx, mixture, start}, stats);
    summarizeEnergies(stats);
    return image;
  }
  RgbImage direct;
  // Training and the direct pass come before the passes (a resumed render has their
  // results in its state). A split render runs them even when stopped: its ranks must make
  // the same collective calls.
  if (!s.resume && (!stopRequested(s.stop) || s.share.split())) {
    if (p.adapt == PmcAdapt::Region) trainRegionTable(scene, s, ctx, mixture, stats);
    direct = renderDirectPass(scene, s, stats);
  }

  PmcPopulation population(setup, PmcPopulation::Config{ctx, chainSettingsOf(chainOf(s)), p, s.seed, &setup.film, chainOf(s).seeds}, mixture, stats);
  const StratifiedPool pool{pixels, uint32_t(s.spp), streamKey(s.seed, kPoolStream, 0)};
  const uint32_t rank = uint32_t(s.share.rank), ranks = uint32_t(std::max(1, s.share.ranks));
  SamplePassHooks passes;
  passes.save = [&](ByteWriter& w) {
    w.put(es), w.put(ps);
    w.put(stats.samples), w.put(stats.rays), w.put(stats.invalidSamples);
    w.putVector(direct.pixels);
    mixture.save(w);
    setup.film.save(w);
    population.save(w);
  };
  passes.load = [&](ByteReader& r) {
    r.get(es), r.get(ps);
    r.get(stats.samples), r.get(stats.rays), r.get(stats.invalidSamples);
    const size_t directPixels = chainOf(s).directSamples > 0 ? size_t(pixels) : 0;
    r.getVector(direct.pixels, directPixels);
    direct.width = directPixels ? s.width : 0, direct.height = directPixels ? s.height : 0;
    mixture.load(r);
    setup.film.load(r);
    population.load(r);
  };
  // Passes [first, end) of this rank are pool rounds rank + ranks * [first, end): the
  // population runs over them to its end, so the state after the group holds no member.
  passes.run = [&](int first, int end, const std::function<void(double)>& progress) {
    const PoolRounds rounds{pool, rank + ranks * uint32_t(first), ranks, uint32_t(end - first)};
    return population.run(rounds, -1, progress, s.stop);
  };
  passes.reduce = [&](const RenderShare& share) {
    setup.film.reduce(share.sumAcrossRanks);
    population.reduce(share.sumAcrossRanks);
    std::vector<double> poolEnergy{ps.poolEnergy};
    share.sumAcrossRanks(poolEnergy);
    ps.poolEnergy = poolEnergy[0];
    sumCounters(share, {&stats.samples, &stats.rays, &stats.invalidSamples, &es.mutations, &es.deposits, &es.rays,
                        &ps.iterations, &ps.drainIterations, &ps.poolSize, &ps.poolUsed, &ps.candidates,
                        &ps.inPlaceSeeds, &ps.membersBorn, &ps.eliminated, &ps.split, &ps.steps});
    for (uint64_t& reason : es.inPlace) sumCounters(share, {&reason});
  };
  auto image = [&](int done, std::vector<std::pair<std::string, RgbImage>>* extras) {
    RgbImage shown = redistributionImage(s, setup.film.resolve(double(done)), direct,
                                         chainOf(s).pmFilterRadius >= 0 ? &population.proposalTally() : nullptr, extras);
    if (extras) addChainMaps(population.tallies(), s.width, s.height, *extras);
    return shown;
  };
  passes.image = [&](int done) { return image(done, nullptr); };
  // A stop inside a group: the population deposited what it held (PmcPopulation::run), the
  // energy of the positions it had taken; each round visits the pixels in a random order, so
  // each pixel is normalised by the mean count of its samples taken.
  RgbImage kept;
  passes.stoppedImage = [&](int done, int, RenderStats& st) {
    st.keptSpp = double(done) + double(population.positionsTaken()) / double(pixels);
    kept = redistributionImage(s, setup.film.resolve(st.keptSpp), direct,
                               chainOf(s).pmFilterRadius >= 0 ? &population.proposalTally() : nullptr, &st.extraImages);
    addChainMaps(population.tallies(), s.width, s.height, st.extraImages);
    return kept;
  };
  renderInSamplePasses(s, pixels, stats, passes);
  summarizeEnergies(stats);
  if (stats.keptSpp > 0) {
    stats.extraImages.emplace_back("strategy", population.strategyImage());
    return kept;
  }
  if (stats.spp == 0) return passes.image(1);  // stopped before the first pass: black
  stats.extraImages.emplace_back("strategy", population.strategyImage());
  return image(stats.spp, &stats.extraImages);
}

IntegratorModule pmcErModule() {
  IntegratorModule m;
  m.name = "pmc-er";
  m.description = "population Monte Carlo energy redistribution (Lai, Fan, Chenney, Dyer), unbiased";
  m.samplePasses = true;
  m.ownTimeBudget = true;
  // The mixture sets the mutation kinds, shapes and sizes; energies come from the pool (no
  // pilot), and its flow has its own option.
  m.options = {
      choiceOption<PmcFlow>("pmc-flow",
                            "equal-deposition (paper figure 2: members are Metropolis chains depositing equally per "
                            "step) or balance (figure 3: members stay, each proposal receives its share times q)",
                            {{"equal-deposition", PmcFlow::EqualDeposition}, {"balance", PmcFlow::Balance}},
                            [](auto& s) -> auto& { return pmcOf(s).flow; }),
      integerOption("population", "members in the population", 1, 10000000, [](auto& s) -> auto& { return pmcOf(s).population; }),
      integerOption("mutations-per-member", "mutations of every member per iteration", 1, 1000000,
                    [](auto& s) -> auto& { return pmcOf(s).mutationsPerMember; }),
      radiiOption(),
      choiceOption<PmcAdapt>("pmc-adapt",
                             "mixture weights per image region, learned by an independent training population and "
                             "frozen (region: unbiased), per member from its own acceptances (member, the paper's: "
                             "can bias), or uniform (off)",
                             {{"region", PmcAdapt::Region}, {"member", PmcAdapt::Member}, {"off", PmcAdapt::Off}},
                             [](auto& s) -> auto& { return pmcOf(s).adapt; }),
      realOption("resample-rate",
                 "share of the population regenerated from the pool per iteration, and of a member's energy "
                 "deposited per iteration",
                 0.001, 1, [](auto& s) -> auto& { return pmcOf(s).resampleRate; }),
      onlyWhen(realOption("alpha-floor", "smallest mixture weight eps (below 1 / the number of radii)", 0, 0.5,
                          [](auto& s) -> auto& { return pmcOf(s).alphaFloor; }),
               [](const RenderSettings& s) {
                 return pmcOf(s).adapt != PmcAdapt::Off ? ""
                                                     : "has no effect on pmc-er with --pmc-adapt off (the weights stay uniform)";
               }),
      realOption("caustic-prob", "probability of the caustic perturbation where it applies (gamma_caustic)", 0, 1,
                 [](auto& s) -> auto& { return pmcOf(s).causticProb; }),
      onlyWhen(integerOption("pmc-region", "region adaptation: side of the square regions in pixels", 1, 65536,
                             [](auto& s) -> auto& { return pmcOf(s).regionSize; }),
               regionAdaptationOnly),
      onlyWhen(integerOption("pmc-train-iterations", "region adaptation: iterations of the training population", 1,
                             100000, [](auto& s) -> auto& { return pmcOf(s).trainIterations; }),
               regionAdaptationOnly),
      realOption("pmc-drain",
                 "once the pool is used up, the population iterates until a member holds at most this share of "
                 "its energy, then deposits the rest where it stands (1: at once)",
                 0, 1, [](auto& s) -> auto& { return pmcOf(s).drainRemainder; }, /*minOpen=*/true),
      directSamplesOption(), seedsOption(), manifoldPerturbationOption()};
  addOptions(m.options, depositOptions());
  m.options.push_back(chainMapsOption());
  m.validate = [](const RenderSettings& s) { validatePmcSettings(pmcOf(s), chainOf(s)); };
  m.render = renderPmcEr;
  m.printSummary = printPmcSummary;
  m.addStats = [](RenderStats& to, const RenderStats& from) {
    addChainStats(chainStatsOf(to), chainStatsOf(from));  // the chain step's counts
    addPmcStats(pmcStatsOf(to), pmcStatsOf(from));
  };
  m.proposalFiltered = true;
  return m;
}

}  // namespace erpt
