#include "erpt/render.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "core/parallel.h"
#include "erpt/erpt_settings.h"
#include "erpt/integrators.h"
#include "integrators/budget_clock.h"
#include "integrators/noise_filters.h"
#include "core/rng.h"
#include "tracer/tracer.h"
#include "sample_passes.h"

namespace erpt {

namespace {

using Clock = std::chrono::steady_clock;
constexpr uint64_t kPassStream = 0x7061737365ull;

double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

RgbImage renderOnce(const Scene& scene, const RenderSettings& s, RenderStats& stats) {
  return integratorNamed(s.integrator).render(scene, s, stats);
}

// Running sum of pass images weighted by their samples per pixel.
struct WeightedSum {
  std::vector<double> sum;
  int width = 0, height = 0;
  void add(const RgbImage& img, double weight) {
    if (sum.empty()) width = img.width, height = img.height, sum.assign(img.pixels.size() * 3, 0.0);
    for (size_t i = 0; i < img.pixels.size(); ++i)
      for (int c = 0; c < 3; ++c) sum[3 * i + size_t(c)] += weight * double(img.pixels[i][c]);
  }
  RgbImage mean(double totalWeight) const {
    RgbImage out;
    out.width = width;
    out.height = height;
    out.pixels.resize(sum.size() / 3);
    for (size_t i = 0; i < out.pixels.size(); ++i)
      out.pixels[i] = Color(float(sum[3 * i] / totalWeight), float(sum[3 * i + 1] / totalWeight),
                            float(sum[3 * i + 2] / totalWeight));
    return out;
  }
};

// Extra images that count per pixel (a time-budgeted render adds them over its passes; the
// others are images, averaged by the passes' samples per pixel, as the acceptance map, which
// is then a mean over the passes rather than over all proposals).
bool isCountImage(const std::string& name) { return name == "proposals" || name == "mutations"; }

RgbImage renderForTime(const Scene& scene, const RenderSettings& s, RenderStats& stats) {
  const double start = budgetSeconds(s);
  const IntegratorModule& module = integratorNamed(s.integrator);
  RenderSettings pass = subRenderSettings(s);
  const PassRenderer renderPass = module.timedPasses ? module.timedPasses(scene, s, stats) : PassRenderer(module.render);
  WeightedSum image;
  std::vector<WeightedSum> extras;
  double notRendering = 0;  // time spent in onPass
  double totalWeight = 0;   // the passes' samples per pixel (kept work counted as RenderStats::keptSpp)
  // The image of all passes so far. The proposed-mutations filter is not linear: it is applied
  // once, to the sum of the passes' chain images and tallies.
  auto resultSoFar = [&]() {
    if (!module.proposalFiltered || chainOf(s).pmFilterRadius < 0) return image.mean(totalWeight);
    RgbImage raw, chains, proposals;
    for (size_t k = 0; k < extras.size(); ++k) {
      const std::string& name = stats.extraImages[k].first;
      if (name == "raw") raw = extras[k].mean(totalWeight);
      if (name == "chains") chains = extras[k].mean(totalWeight);
      if (name == "proposals") proposals = extras[k].mean(1.0);  // a count
    }
    return proposalFilteredImage(raw, chains, proposals, chainOf(s).pmFilterRadius);
  };
  int passSpp = 1;
  for (int p = 0;; ++p) {
    pass.spp = passSpp;
    pass.seed = p == 0 ? s.seed : streamKey(s.seed, kPassStream, uint64_t(p));
    if (module.scaleTimedPass) module.scaleTimedPass(s, pass);
    const double passStart = budgetSeconds(s);
    RenderStats ps;
    const RgbImage img = renderPass(scene, pass, ps);
    const double passSeconds = budgetSeconds(s) - passStart;
    // A stopped pass counts with the sample passes it completed (sample_passes.h), or with
    // the samples per pixel its kept work stands for (RenderStats::keptSpp).
    double weight = passSpp;
    if (ps.partial) {
      stats.partial = true;
      passSpp = ps.spp;
      weight = ps.keptSpp > 0 ? ps.keptSpp : double(ps.spp);
      if (!(weight > 0)) break;
      if (ps.keptSpp > 0) stats.keptSpp = totalWeight + weight;
    }
    totalWeight += weight;
    image.add(img, weight);
    extras.resize(ps.extraImages.size());
    for (size_t k = 0; k < ps.extraImages.size(); ++k)  // counts add up, images average
      extras[k].add(ps.extraImages[k].second, isCountImage(ps.extraImages[k].first) ? 1.0 : weight);
    if (p == 0)
      for (const auto& [name, extra] : ps.extraImages) stats.extraImages.emplace_back(name, RgbImage{});
    stats.samples += ps.samples;
    stats.rays += ps.rays;
    stats.invalidSamples += ps.invalidSamples;
    for (const auto& [name, seconds] : ps.stages.all()) stats.stages.add(name, seconds);
    if (module.addStats) module.addStats(stats, ps);
    stats.spp += passSpp;
    stats.passes = p + 1;

    const double elapsed = budgetSeconds(s) - start - notRendering;
    if (s.onPass) {
      const double t = budgetSeconds(s);
      s.onPass(resultSoFar(), elapsed, stats.spp);
      notRendering += budgetSeconds(s) - t;
    }
    if (s.progress) s.progress(std::min(1.0, elapsed / s.timeBudget));
    if (stats.partial) break;
    const double perSample = passSeconds / passSpp;  // includes the pass's fixed costs: cautious
    const double fits = (s.timeBudget - elapsed) / perSample;
    if (!(fits >= 1)) break;
    passSpp = int(std::min({2.0 * passSpp, std::floor(fits), double(1 << 24)}));
  }
  if (!(totalWeight > 0)) {  // stopped in the first pass, keeping nothing
    RgbImage none;
    none.width = s.width, none.height = s.height;
    none.pixels.assign(size_t(s.width) * size_t(s.height), Color(0.0f));
    stats.extraImages.clear();
    return none;
  }
  for (size_t k = 0; k < extras.size(); ++k)
    stats.extraImages[k].second = extras[k].mean(isCountImage(stats.extraImages[k].first) ? 1.0 : totalWeight);
  return resultSoFar();
}

}  // namespace

RenderSettings resolveSettings(const Scene& scene, RenderSettings s) {
  if (s.width <= 0) s.width = scene.film.width;
  if (s.height <= 0) s.height = scene.film.height;
  if (s.spp <= 0) s.spp = scene.integrator.spp;
  if (s.maxDepth == -2) s.maxDepth = scene.integrator.maxDepth;
  if (!s.filterSet) s.filter = scene.film.filter;
  return s;
}

std::shared_ptr<const Tracer> buildTracer(const Scene& scene, int threads) {
  ThreadPool pool(threads);  // the BVH build uses the threads the render may use
  return std::make_shared<const Tracer>(scene);
}

RgbImage render(const Scene& scene, const RenderSettings& requested, RenderStats& stats) {
  RenderSettings s = resolveSettings(scene, requested);
  const IntegratorModule& integrator = integratorNamed(s.integrator);
  // Before the BVH build, to fail fast: each declared option's range, then the integrator's
  // rules between options.
  for (const OptionSpec& option : integrator.options) checkOptionRange(option, s);
  integrator.validate(s);
  if (!s.tracer) {
    const Clock::time_point buildStart = Clock::now();
    s.tracer = buildTracer(scene, s.threads);
    stats.buildSeconds = secondsSince(buildStart);
  }
  // The render's time (and a --time budget) starts once the scene is built.
  const Clock::time_point start = Clock::now();
  if (s.timeBudget != 0 && (!(s.timeBudget > 0) || s.timeBudget > 1e7))
    throw UsageError("--time must be in (0, 10000000] seconds");
  if (s.share.split() && s.timeBudget != 0)
    throw UsageError("a render over several processes needs a fixed --spp, not --time");
  if ((s.resume || s.onPasses) && s.timeBudget != 0) throw UsageError("checkpoints need a fixed --spp, not --time");
  const uint64_t refusedBefore = s.tracer->refusedRays();
  RgbImage image;
  if (s.timeBudget != 0 && !integrator.ownTimeBudget) {
    image = renderForTime(scene, s, stats);
  } else {
    image = renderOnce(scene, s, stats);  // stats.spp: the passes it completed
    stats.passes = 1;
  }
  stats.refusedRays = s.tracer->refusedRays() - refusedBefore;
  stats.seconds = secondsSince(start);
  return image;
}

std::string partialRenderNote(const RenderSettings& r, const RenderStats& stats) {
  char text[320];
  const char* kept = stats.keptSpp > 0 ? ", each chain stopped part-way leaving its remaining energy where it stood" : "";
  if (r.timeBudget > 0)
    std::snprintf(text, sizeof text, "%.*f samples per pixel in %d passes, stopped %.1f s into a %g s budget%s",
                  stats.keptSpp > 0 ? 2 : 0, stats.keptSpp > 0 ? stats.keptSpp : double(stats.spp), stats.passes,
                  stats.seconds, r.timeBudget, kept);
  else if (stats.keptSpp > 0)
    std::snprintf(text, sizeof text, "%.1f%% of the render's work (%d of %d sample passes complete, then the seeds the chains "
                  "had taken)%s", 100.0 * stats.keptSpp / std::max(1, r.spp), stats.spp, r.spp, kept);
  else
    std::snprintf(text, sizeof text, "%d of %d samples per pixel", stats.spp, r.spp);
  return text;
}

}  // namespace erpt
