// Sample passes: how every integrator's render is ordered so that they can stop early,
// show their progress and resume (docs/long-renders.md).
//
// Pass j gives every pixel its sample j (pixels in tiled order). After k passes every pixel
// has k samples, each of them uniform over the pixel's strata (generate_camera_rays.cpp
// permutes both stratum indices per pixel), so the image of k passes is an unbiased render
// at k samples per pixel. Passes run in groups (small images group several, so that a group
// fills the wavefront's batches); after each group the integrator's state can be saved. A stop
// part-way through a group rolls the state back to the group's start.
#pragma once

#include <functional>
#include <initializer_list>
#include <string>
#include <vector>

#include "core/byte_stream.h"
#include "erpt/render.h"
#include "integrators/path/path_integrator.h"

namespace erpt {

struct SamplePassHooks {
  std::function<void(ByteWriter&)> save;
  std::function<void(ByteReader&)> load;
  // Renders passes [first, end), reporting the fraction done of them; returns false if the
  // render was stopped before they completed (the driver then loads the last saved state).
  std::function<bool(int first, int end, const std::function<void(double)>& progress)> run;
  // The image of the state after `passes` passes.
  std::function<RgbImage(int passes)> image;
  // When set, a stop inside the first group keeps its work instead of returning nothing (the
  // chain integrators, RenderStats::keptSpp): the image of the state after `done` complete
  // passes (0, or those of a checkpoint) and the stopped group [done, end). Sets
  // stats.keptSpp. A stop after a completed group rolls back to it (an unbiased image of its
  // passes), and split renders always roll back (their ranks stop at different points).
  std::function<RgbImage(int done, int end, RenderStats& stats)> stoppedImage;
  // Split renders (RenderShare): adds the accumulators (film sums, counts) over the ranks.
  std::function<void(const RenderShare&)> reduce;
};

// Runs settings.spp passes (from settings.resume when set) through the hooks; sets
// stats.spp, stats.partial. A split render (settings.share) runs this rank's passes, then
// reduces, and returns the image of all ranks' passes.
RgbImage renderInSamplePasses(const RenderSettings& settings, size_t pixels, RenderStats& stats,
                              const SamplePassHooks& hooks);

// Sample k of passes [first, end) of this rank: sample pass(first + k / P) of pixel
// order[k % P], P = order.size(), where this rank's pass i is rank + i * ranks.
PathSampleSet passSamples(const std::vector<uint32_t>& order, int first, int end, const RenderShare& share);
// How many of `total` passes a rank renders.
int passesOfRank(int total, const RenderShare& share);

// A render inside a render (pilot, direct pass, time-budget pass): it shares the stop flag
// but reports no progress and keeps no state of its own.
inline RenderSettings subRenderSettings(const RenderSettings& s) {
  RenderSettings sub = s;
  sub.progress = nullptr;
  sub.onPasses = nullptr;
  sub.resume = nullptr;
  sub.onPass = nullptr;
  sub.timeBudget = 0;
  sub.seeds = nullptr;
  sub.seedSink = nullptr;
  return sub;
}

// Split renders: each counter becomes its total over the ranks (exact below 2^53).
void sumCounters(const RenderShare& share, std::initializer_list<uint64_t*> counters);

// save, load and reduce for a render whose whole state is a film (Film or SplatFilm: save,
// load, reduce) and the common counters: the path tracer, `direct`, BDPT.
template <class FilmT>
void setFilmStateHooks(SamplePassHooks& passes, FilmT& film, RenderStats& stats) {
  passes.save = [&film, &stats](ByteWriter& w) {
    film.save(w);
    w.put(stats.samples), w.put(stats.rays), w.put(stats.invalidSamples);
  };
  passes.load = [&film, &stats](ByteReader& r) {
    film.load(r);
    r.get(stats.samples), r.get(stats.rays), r.get(stats.invalidSamples);
  };
  passes.reduce = [&film, &stats](const RenderShare& share) {
    film.reduce(share.sumAcrossRanks);
    sumCounters(share, {&stats.samples, &stats.rays, &stats.invalidSamples});
  };
}

inline bool stopRequested(const std::atomic<bool>* stop) { return stop && stop->load(std::memory_order_relaxed); }

}  // namespace erpt
