// The parts ERPT, PMC-ER and MLT share around their chains (redistribution_parts.h).
#include "integrators/redistribution_parts.h"

#include <algorithm>
#include <cmath>

#include "core/rng.h"
#include "erpt/error.h"
#include "integrators/direct/direct_integrator.h"
#include "integrators/noise_filters.h"
#include "integrators/sample_passes.h"
#include "integrators/seed_sampler.h"

namespace erpt {

namespace {
constexpr uint64_t kDirectStream = 0x646972656374ull;
}  // namespace

void validateChainOptions(const ChainOptions& o) {
  if (o.directSamples == 0) throw UsageError("--direct-samples must be -1 (the chains render direct light too) or at least 1");
}

RgbImage renderDirectPass(const Scene& scene, const RenderSettings& s, RenderStats& stats) {
  if (chainOf(s).directSamples <= 0) return RgbImage{};
  RenderSettings direct = subRenderSettings(s);
  direct.spp = chainOf(s).directSamples;
  // Its own random stream: the main pass's keys would correlate the two estimates.
  direct.seed = streamKey(s.seed, kDirectStream, 0);
  RenderStats directStats;
  RgbImage d;
  if (chainOf(s).seeds == SeedSampler::Bdpt) {
    // BDPT's paths of at most two segments: what the chains leave out (seedForChains).
    direct.maxDepth = s.maxDepth < 0 ? 2 : std::min(2, s.maxDepth);
    d = renderWithSeedSampler(scene, direct, directStats);
  } else {
    d = renderDirect(scene, direct, directStats);
  }
  stats.rays += directStats.rays;
  for (const auto& [name, seconds] : directStats.stages.all()) stats.stages.add("direct " + name, seconds);
  return d;
}

RgbImage redistributionImage(const RenderSettings& s, RgbImage image, const RgbImage& direct,
                             const std::vector<uint32_t>* tally, std::vector<std::pair<std::string, RgbImage>>* extras) {
  RgbImage chainsOnly, counts;
  if (tally) {
    // The filter rescales what the chains deposited (not the direct pass) and needs it apart.
    chainsOnly = image;
    counts.width = s.width;
    counts.height = s.height;
    for (uint32_t t : *tally) counts.pixels.push_back(Color(float(t)));
  }
  if (!direct.pixels.empty())
    for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] += direct.pixels[i];
  if (!tally) return image;
  RgbImage filtered = proposalFilteredImage(image, chainsOnly, counts, chainOf(s).pmFilterRadius);
  if (extras) {
    // Keep the unfiltered image and the chains' part for the user (and for time-budgeted
    // renders, which filter the sum of their passes).
    extras->emplace_back("proposals", std::move(counts));
    extras->emplace_back("raw", std::move(image));
    extras->emplace_back("chains", std::move(chainsOnly));
  }
  return filtered;
}

void addChainMaps(const ProposalTallies& tallies, int width, int height,
                  std::vector<std::pair<std::string, RgbImage>>& extras) {
  if (tallies.acceptance.empty()) return;
  RgbImage mutations{width, height, {}, {}}, acceptance{width, height, {}, {}};
  for (size_t i = 0; i < tallies.proposals.size(); ++i) {
    const double n = tallies.proposals[i];
    mutations.pixels.push_back(Color(float(n)));
    acceptance.pixels.push_back(Color(n > 0 ? float(double(tallies.acceptance[i]) * kAcceptanceUnit / n) : 0.0f));
  }
  extras.emplace_back("mutations", std::move(mutations));
  extras.emplace_back("acceptance", std::move(acceptance));
}

void scaleDirectSamples(const RenderSettings& whole, RenderSettings& pass) {
  if (chainOf(whole).directSamples > 0)
    chainOf(pass).directSamples = std::max(1, int(std::lround(double(chainOf(whole).directSamples) * pass.spp / whole.spp)));
}

}  // namespace erpt
