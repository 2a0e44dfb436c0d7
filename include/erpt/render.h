// Rendering entry point shared by the CLI, tests and benchmarks.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "erpt/image_io.h"
#include "erpt/per_integrator.h"
#include "erpt/render_state.h"
#include "erpt/scene.h"
#include "erpt/stage_times.h"

namespace erpt {

class Tracer;
struct SeedStore;

// A render split over processes (MPI; docs/long-renders.md, "Many machines"): this process
// renders the sample passes j with j % ranks == rank, and sumAcrossRanks replaces a vector by
// its element-wise sum over all ranks, added in rank order, on every rank (a collective call:
// every rank makes the same calls in the same order).
struct RenderShare {
  int rank = 0, ranks = 1;
  std::function<void(std::vector<double>&)> sumAcrossRanks;
  bool split() const { return ranks > 1; }
};

struct RenderSettings {
  std::string integrator = "path";
  int width = 0, height = 0;  // 0: the scene's film size
  int spp = 0;                // 0: the scene's sample count
  int maxDepth = -2;          // -2: the scene's value
  uint64_t seed = 0;
  int threads = 0;            // 0: all hardware threads
  bool filterSet = false;     // false: the scene's rfilter
  FilterKind filter = FilterKind::Box;
  // The path tracer's film (film_splat.h): Auto picks per filter. ERPT and PMC-ER use Fis.
  FilmMode film = FilmMode::Auto;
  // Called with the fraction done as the render goes (chains too), from one rendering thread
  // at a time.
  std::function<void(double fraction)> progress;
  SeedStore* seeds = nullptr;  // path tracer: when set, every contribution is recorded as a seed
  // Path tracer with `seeds` set: called after every batch with that batch's seeds, which are
  // then cleared (streaming, so memory stays bounded). Unset: the store keeps all seeds.
  std::function<void(SeedStore&)> seedSink;
  // Each integrator's own options (erptOf(s), pmcOf(s), mltOf(s)), and the options the chain
  // integrators share (chainOf(s): direct split, deposits, filters, perturbations).
  PerIntegrator options;
  // The Embree scene. render() builds it once and every pass and sub-render (ERPT's pilot,
  // seed and direct passes, time-budgeted passes) shares it; unset: the integrator builds one.
  std::shared_ptr<const Tracer> tracer;
  // > 0: render for this many seconds of wall-clock time instead of `spp` samples per pixel
  // (see render()). The image then depends on the machine's speed.
  double timeBudget = 0;
  // Time-budgeted renders: called after every pass with the image so far, the render's
  // seconds so far (not counting this call) and its samples per pixel so far.
  std::function<void(const RgbImage&, double seconds, int spp)> onPass;
  // The clock a time budget's decisions read, in seconds from any origin (unset: the steady
  // clock). Tests set a counting clock so that the passes or rounds a budget takes do not
  // depend on the machine's speed.
  std::function<double()> budgetClock;
  // Stopping early (path, direct, erpt): once *stop is true, the render ends at its next batch
  // and returns the image of the sample passes it completed (RenderStats::partial). The
  // pass under way is dropped, so every pixel has the same samples and the image is an
  // unbiased render at fewer samples per pixel. A signal handler may set it.
  const std::atomic<bool>* stop = nullptr;
  // Called after every group of completed sample passes (and once before the first, with the
  // state the render starts from) with the state and a function resolving its image.
  std::function<void(const RenderState&, const std::function<RgbImage()>& image)> onPasses;
  // Continue from this state (a checkpoint of the same scene and settings) instead of from
  // nothing: the result is bit-identical to the uninterrupted render.
  const RenderState* resume = nullptr;
  // Sample passes run in groups of at least this many samples (0: 131072, one batch of the
  // path tracer); states are saved and a stop falls back only between groups.
  size_t passGroupSamples = 0;
  // One of several processes rendering the image together: the returned
  // image, stats.spp and stats.samples are the whole render's, on every rank.
  RenderShare share;
};

struct RenderStats {
  // The render's wall time, and apart from it the time render() spent building the Embree
  // scene when RenderSettings::tracer was unset (not part of `seconds` nor of a --time budget).
  double seconds = 0, buildSeconds = 0;
  uint64_t samples = 0;
  uint64_t rays = 0;
  uint64_t invalidSamples = 0;  // NaN/Inf estimates, dropped and counted
  uint64_t refusedRays = 0;     // rays the tracer would not trace (kRefusedRay), over the render
  StageTimes stages;
  // Each integrator's own statistics (pmcStatsOf(stats), mltStatsOf(stats)), and the chain
  // integrators' shared counts of their chain steps (chainStatsOf(stats)).
  PerIntegrator own;
  int spp = 0;  // samples per pixel rendered (time-budgeted renders choose it)
  int passes = 0;
  // Stopped early (RenderSettings::stop): `spp` samples per pixel of the requested ones were
  // rendered and the image is normalised by them.
  bool partial = false;
  // A chain integrator (erpt, pmc-er, mlt) stopped before its first group of passes completed
  // keeps that group's work (docs/long-renders.md, "Stopping"): every chain left deposits its
  // remaining energy where it stands, so the image holds the energy of every seed taken. This is then
  // the samples per pixel that image stands for, on average over the pixels (mlt, whose
  // deposits always add up to its whole image: the share of its steps run times the spp),
  // more than `spp`; 0 when the image is of complete passes only.
  double keptSpp = 0;
  // Images the integrator makes besides the result, by name (ERPT's proposed-mutations filter:
  // "raw", the unfiltered image, and "proposals", the tally); the CLI writes OUT-name.exr.
  std::vector<std::pair<std::string, RgbImage>> extraImages;
};

// Settings with the scene's values filled in where the caller left them open.
RenderSettings resolveSettings(const Scene& scene, RenderSettings settings);
// Throws UsageError for an unknown integrator.
//
// With a time budget the integrator runs in passes, each an independent render with its own
// random stream, and the image is their average weighted by samples per pixel (each pass is
// unbiased, so the average is). Passes start at 1 spp and double while the time left allows,
// judged by the last pass's time per sample; no pass is started that is predicted to end
// after the budget, so the render ends a little before it (or after it, if even one sample
// per pixel takes longer). ERPT keeps its configured ratio of mutations to seeds in every
// pass: e_ave comes from one pilot pass, e_d = spp e_ave / M from the configured spp, and the
// direct pass gets directSamples x (pass spp) / spp samples per pixel.
// The Embree scene of `scene` (built with `threads`, 0: all cores), for RenderSettings::tracer:
// a front end that renders one scene several times builds it once.
std::shared_ptr<const Tracer> buildTracer(const Scene& scene, int threads);

RgbImage render(const Scene& scene, const RenderSettings& settings, RenderStats& stats);

// What a stopped render's image holds, for its metadata and messages ("12 of 32 samples per
// pixel", with a time budget "79 samples per pixel in 7 passes of a 10 s budget"), from the
// resolved settings and the render's stats.
std::string partialRenderNote(const RenderSettings& resolved, const RenderStats& stats);

}  // namespace erpt
