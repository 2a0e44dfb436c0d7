// `--integrator erpt`: Energy Redistribution Path Tracing (Cline, Talbot, Egbert 2005,
// figure 7) with the equal deposition flow rule.
//
//   1. Pilot pass: a path tracer with its own random stream estimates e_ave, the mean energy
//      of the seeds per pixel sample; e_d = n e_ave / M (eq. 7). It only sets the run time.
//   2. Main pass: the wavefront path tracer at n samples per pixel streams its seeds, batch by
//      batch, into the chain machine (erpt_chains.h), which starts floor(U + e / (m e_d))
//      chains per seed and runs them; pixel value = sum of deposits / n.
//   3. Optional (--direct-samples N): paths of at most one bounce are left out of the seeds
//      and rendered by the stratified direct-lighting integrator instead (as Mitsuba does).
#include "erpt_integrator.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "direct_integrator.h"
#include "erpt/rng.h"
#include "erpt/erpt_chains.h"
#include "erpt/noise_filters.h"
#include "erpt/seed_checks.h"
#include "path_integrator.h"
#include "render_setup.h"

namespace erpt {

namespace {
constexpr uint64_t kPilotStream = 0x70696c6f74ull, kDirectStream = 0x646972656374ull;
}  // namespace

void validateErptSettings(const ErptSettings& o) {
  if (o.mutationsPerPixel < 1) throw UsageError("--mutations-per-pixel must be at least 1");
  if (o.chainLength < 1) throw UsageError("--chain-length must be at least 1");
  if (!(o.lensRadius > 0) || !(o.lensRadius <= 1e4f)) throw UsageError("--lens-radius must be in (0, 10000] pixels");
  if (o.pilotSpp < 1) throw UsageError("--pilot-spp must be at least 1");
  if (o.directSamples == 0 || o.directSamples < -1)
    throw UsageError("--direct-samples must be -1 (ERPT renders direct light too) or at least 1");
  if (o.pmFilterRadius < -1 || o.pmFilterRadius > 1000) throw UsageError("--pm-filter-radius must be in [0, 1000] pixels");
  if (o.maxChainsPerSeed < 1 || o.maxChainsPerSeed > 1000000)
    throw UsageError("--max-chains-per-seed must be in [1, 1000000]");
  if (o.maxConsecutive < 0) throw UsageError("--max-consecutive must be at least 1 (or 0: off)");
  if (o.maxConsecutive > 0 && o.flow == FlowRule::DetailedBalance)
    throw UsageError("--max-consecutive needs moving chains: it does not apply to --flow detailed-balance");
}

// e_ave: mean energy per pixel sample of the seeds ERPT will redistribute.
double erptPilotEnergy(const Scene& scene, const RenderSettings& s, RenderStats& stats) {
  validateErptSettings(s.erpt);
  RenderSettings pilot = s;
  pilot.spp = s.erpt.pilotSpp;
  pilot.seed = streamKey(s.seed, kPilotStream, 0);
  pilot.progress = nullptr;
  SeedStore store;
  pilot.seeds = &store;
  double energy = 0;
  const bool excludeDirect = s.erpt.directSamples > 0;
  pilot.seedSink = [&](SeedStore& batch) {
    for (size_t i = 0; i < batch.size(); ++i) {
      if (!seedForChains(batch, i, excludeDirect)) continue;
      const float e = luminance(batch.contribution(i));
      if (e > 0 && std::isfinite(e)) energy += e;
    }
  };
  RenderStats pilotStats;
  renderPath(scene, pilot, pilotStats);
  stats.rays += pilotStats.rays;
  return energy / (double(s.width) * s.height * pilot.spp);
}

RgbImage renderErpt(const Scene& scene, const RenderSettings& s, RenderStats& stats) {
  const ErptSettings& o = s.erpt;
  validateErptSettings(o);
  ErptStats& es = stats.erpt;
  es.pilotEnergy = o.knownPilotEnergy >= 0 ? o.knownPilotEnergy : erptPilotEnergy(scene, s, stats);
  es.depositEnergy = o.knownDepositEnergy > 0 ? o.knownDepositEnergy : double(s.spp) * es.pilotEnergy / o.mutationsPerPixel;

  RenderSetup setup(scene, s);
  FilmDensity density(setup.filter, s.width, s.height);
  ErptChains::Config config{ErptStepContext{MeasureContext{scene, setup.lights, setup.camera, density}, o}, s.seed,
                            erptChainSlots(setup.pool.threads()), es.depositEnergy};
  ErptChains chains(setup.tracer, config, setup.film, es, stats.stages);

  RenderSettings main = s;
  SeedStore store;
  main.seeds = &store;
  double inChains = 0;
  // Every seed goes to the chain machine, also when e_d = 0 (the pilot found no energy): it
  // then deposits the seeds where they are, so no energy is lost.
  main.seedSink = [&](SeedStore& batch) {
    auto t = std::chrono::steady_clock::now();
    chains.consume(batch);
    inChains += std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
  };
  RenderStats seedStats;
  renderPath(scene, main, seedStats);
  auto t = std::chrono::steady_clock::now();
  chains.finish();
  inChains += std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
  es.erptSeconds = inChains;
  stats.samples = seedStats.samples;
  stats.rays += seedStats.rays + es.rays;
  stats.invalidSamples = seedStats.invalidSamples;
  for (const auto& [name, seconds] : seedStats.stages.all()) stats.stages.add("seed " + name, seconds);
  return finishRedistribution(scene, s, stats, setup.film.resolve(double(s.spp)),
                              o.pmFilterRadius >= 0 ? &chains.proposalTally() : nullptr);
}

RgbImage finishRedistribution(const Scene& scene, const RenderSettings& s, RenderStats& stats, RgbImage image,
                              const std::vector<uint32_t>* tally) {
  const ErptSettings& o = s.erpt;
  RgbImage chainsOnly;
  if (tally) {
    // The filter rescales what the chains deposited (not the direct pass) and needs it apart.
    chainsOnly = image;
    RgbImage counts;
    counts.width = s.width;
    counts.height = s.height;
    for (uint32_t t : *tally) counts.pixels.push_back(Color(float(t)));
    stats.extraImages.emplace_back("proposals", std::move(counts));
  }
  if (o.directSamples > 0) {
    RenderSettings direct = s;
    direct.spp = o.directSamples;
    // Its own random stream: the main pass's keys would correlate the two estimates.
    direct.seed = streamKey(s.seed, kDirectStream, 0);
    direct.progress = nullptr;
    RenderStats directStats;
    RgbImage d = renderDirect(scene, direct, directStats);
    for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] += d.pixels[i];
    stats.rays += directStats.rays;
    for (const auto& [name, seconds] : directStats.stages.all()) stats.stages.add("direct " + name, seconds);
  }
  if (tally) {
    // Keep the unfiltered image and the chains' part for the user (and for time-budgeted
    // renders, which filter the sum of their passes).
    const RgbImage counts = stats.extraImages.back().second;
    RgbImage filtered = proposalFilteredImage(image, chainsOnly, counts, o.pmFilterRadius);
    stats.extraImages.emplace_back("raw", std::move(image));
    stats.extraImages.emplace_back("chains", std::move(chainsOnly));
    return filtered;
  }
  return image;
}

}  // namespace erpt
