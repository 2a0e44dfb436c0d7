// `--integrator path`: the wavefront path tracer (BSDF importance sampling, next-event
// estimation with MIS, Russian roulette). It is also the Monte Carlo seed sampler of ERPT.
//
// A wavefront is a queue of paths in flight. Each bounce runs the stages
//   intersect -> shade -> shadow (occlusion stream) -> compact
// over its live slots; a path that ends gives its slot to the next sample at once (path
// regeneration, as in Cycles), so the ray streams stay full instead of draining to a tail.
// Rendering, every task of the thread pool runs its own small wavefront (kTaskQueue paths,
// cache-resident) over a chunk of samples, with no synchronisation per bounce. Recording
// seeds (ERPT's seed pass), one wavefront of a whole batch runs each stage across the threads
// and drains before the batch's seeds go to the sink. Either way each sample's radiance lands
// at its index in the batch, and the film adds a batch in sample order: the image does not
// depend on the thread count or on how the wavefronts were scheduled.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <numeric>
#include <optional>

#include "core/parallel.h"
#include "models/film.h"
#include "models/film_splat.h"
#include "stages/stages.h"
#include "tracer/tracer.h"
#include "integrators/path/path_integrator.h"
#include "render_setup.h"
#include "sample_passes.h"

namespace erpt {

namespace {
constexpr size_t kBatchPaths = 1 << 17;  // samples that reach the film (and the seed sink) together
// Recording seeds, a batch's vertex history and seed store grow with the batch: at 2^17 samples
// they took some 250 MB, touched afresh (page faults) and copied as they grew, on one thread.
// At 2^15 an ERPT render's memory fell to a third and its time on 2 threads by a fifth
// (docs/performance.md, "Chains on two threads").
constexpr size_t kSeedBatchPaths = 1 << 15;
// What a seed-recording batch reserves per path (traceSamples): vertices of its history, seeds
// (two per bounce: next-event and emission), and their vertices.
constexpr size_t kHistoryRowsPerPath = 8, kSeedsPerPath = 8, kSeedVerticesPerPath = 32;
constexpr size_t kChunkSamples = 16384;  // one task's share of a batch
constexpr size_t kTaskQueue = 4096;      // paths in flight in one task's wavefront
constexpr size_t kGrain = 512;

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The queues of one wavefront, and the per-slot inputs and outputs of its camera-ray stage.
struct PathWavefront {
  PathQueue paths;
  PathSlotQueue slots[2];
  RayQueue rays[2], shadowRays;
  HitQueue hits;
  std::vector<uint32_t> startPixel, startSample, freeIds, ended;
  std::vector<float> startX, startY;
  size_t capacity = 0;

  void reserve(size_t n) {
    if (capacity == n) return;
    capacity = n;
    paths.resize(n);
    for (int b = 0; b < 2; ++b) {
      slots[b].resize(n);
      prepareRays(rays[b], n);
    }
    prepareRays(shadowRays, n);
    hits.resize(n);
    for (auto* v : {&startPixel, &startSample, &ended}) v->resize(n);
    startX.resize(n);
    startY.resize(n);
  }
};

// Radiance and film position of every sample of a batch, by index in the batch.
struct BatchRadiance {
  std::vector<uint32_t> pixel;
  std::vector<float> x, y, r, g, b;
  void resize(size_t n) {
    pixel.resize(n);
    for (auto* v : {&x, &y, &r, &g, &b}) v->resize(n);
  }
  Color at(size_t i) const { return Color(r[i], g[i], b[i]); }
};

// Runs a stage over [0, n): across the threads (forEachRange) or inline in the calling task.
struct StageRunner {
  bool parallel;
  StageTimes& times;
  template <class Fn>
  void operator()(const char* stage, size_t n, const Fn& fn) const {
    if (parallel) return forEachRange(stage, n, kGrain, fn, &times);
    const auto start = std::chrono::steady_clock::now();
    if (n > 0) fn(IndexRange{0, n});
    times.add(stage, secondsSince(start));
  }
  size_t grain(size_t n) const { return parallel ? kGrain : std::max<size_t>(n, 1); }
};

// Seed recording: where the seeds go and the batch's vertex history (kept by the caller
// from batch to batch: allocated afresh, its pages cost about a tenth of an ERPT render).
struct SeedRecording {
  SeedStore& seeds;
  VertexQueue& history;
  SeedPlacement& placement;
};

// Starts samples first + j (j in r) in the free path ids freeIds[j], in slots firstSlot + j.
void startPaths(PathWavefront& w, int cur, const StageContext& ctx, const PathSampleSet& samples, size_t first,
                size_t firstSlot, IndexRange r) {
  PathQueue& paths = w.paths;
  for (size_t j = r.begin; j < r.end; ++j) {
    const uint32_t id = w.freeIds[j];
    const size_t slot = firstSlot + j;
    uint32_t pixel, sample;
    samples.at(first + j, pixel, sample);
    startPath(paths, id, sampleStream(ctx, pixel, sample), pixel, sample);
    paths.runIndex[id] = uint32_t(first + j);
    w.slots[cur].path[slot] = id;
    w.startPixel[slot] = paths.pixel[id];
    w.startSample[slot] = paths.sample[id];
  }
}

// Seed recording: the eye vertex of path id i is vertex i of the history.
// The eye vertex of each new path: its camera ray's origin (the pinhole, or the lens point a
// thin lens sampled), which ERPT's chains keep.
void writeEyeVertices(VertexQueue& history, PathQueue& paths, const RayQueue& cameraRays, size_t firstSlot,
                      const uint32_t* ids, IndexRange r) {
  VertexQueue::Row v;  // kind kEyeVertex, no material, no emitter, no parent
  v.pdfForward = 1;  // the camera ray: density of the film position (filter-sampled)
  for (size_t j = r.begin; j < r.end; ++j) {
    v.p = cameraRays.orgAt(firstSlot + j);
    history.setRow(ids[j], v);
    paths.lastVertex[ids[j]] = int32_t(ids[j]);
  }
}

// Traces samples [first, first + count) through wavefront `w` with `capacity` paths in flight.
// Each sample's radiance goes to out[sample - outFirst]. Recording seeds, count <= capacity:
// all samples start at once and the wavefront drains.
void traceSamples(const Tracer& tracer, const StageContext& ctx, const PathSampleSet& samples, size_t first,
                  size_t count, size_t capacity, PathWavefront& w, const StageRunner& run, BatchRadiance& out,
                  size_t outFirst, SeedRecording* rec, std::atomic<uint64_t>& rayCount) {
  w.reserve(capacity);
  w.freeIds.resize(capacity);
  std::iota(w.freeIds.begin(), w.freeIds.end(), 0u);
  if (rec) {
    // Room up front for what a batch of diffuse paths records, so that the columns are not
    // copied as they grow (one thread, onto pages touched afresh): address space only, whose
    // pages the parallel stages that write the rows touch first. Longer paths grow beyond it.
    rec->history.reserve(kHistoryRowsPerPath * capacity);
    rec->seeds.seeds.reserve(kSeedsPerPath * capacity);
    rec->seeds.vertices.reserve(kSeedVerticesPerPath * capacity);
  }
  VertexHistory bounceHistory{rec ? &rec->history : nullptr, 0};
  size_t next = first, live = 0;
  int cur = 0;
  while (live > 0 || next < first + count) {
    // Regeneration: the next samples take the free path ids, in slots after the live ones.
    const size_t firstNew = live;
    const size_t m = std::min(w.freeIds.size(), first + count - next);
    if (m > 0) {
      if (rec) {
        rec->history.resize(m);
        bounceHistory.base = m;
      }
      run("generate", m, [&](IndexRange r) {
        startPaths(w, cur, ctx, samples, next, live, r);
        const IndexRange slotRange{live + r.begin, live + r.end};
        stageGenerateCameraRays(ctx, w.startPixel.data(), w.startSample.data(), w.rays[cur], slotRange, w.startX.data(),
                                w.startY.data());
        for (size_t j = r.begin; j < r.end; ++j) {
          w.paths.filmX[w.freeIds[j]] = w.startX[live + j];
          w.paths.filmY[w.freeIds[j]] = w.startY[live + j];
        }
        if (rec) writeEyeVertices(rec->history, w.paths, w.rays[cur], live, w.freeIds.data(), r);
      });
      w.freeIds.erase(w.freeIds.begin(), w.freeIds.begin() + ptrdiff_t(m));
      live += m;
      next += m;
    }

    // The shade stage writes the row of every hit it shades; the rows it leaves (misses,
    // refused rays) are never linked to, so they need no zeroing.
    if (rec) rec->history.resizeForOverwrite(bounceHistory.base + live);
    rayCount += live;
    run("intersect", live, [&](IndexRange r) {
      // Bounce rays of the paths in flight are incoherent; the camera rays just started are not.
      const size_t split = std::clamp(firstNew, r.begin, r.end);
      if (split > r.begin) tracer.intersect(w.rays[cur], w.hits, IndexRange{r.begin, split}, RayCoherence::Incoherent);
      if (r.end > split) tracer.intersect(w.rays[cur], w.hits, IndexRange{split, r.end}, RayCoherence::Coherent);
    });
    run("shade", live, [&](IndexRange r) {
      stageShadePath(ctx, w.paths, w.slots[cur], w.rays[cur], w.hits, w.shadowRays, bounceHistory, r);
    });
    run("shadow", live, [&](IndexRange r) {
      uint64_t traced = 0;
      for (size_t k = r.begin; k < r.end; ++k) traced += w.shadowRays.tnear[k] <= w.shadowRays.tfar[k];
      rayCount += traced;
      tracer.occluded(w.shadowRays, r);
      stageShadowResolve(w.shadowRays, w.slots[cur], w.paths, r);
    });
    if (rec) {
      rec->placement.seed.resize(live);
      rec->placement.vertex.resize(live);
      run("record seeds", live, [&](IndexRange r) {
        stageCountSeeds(w.slots[cur], w.shadowRays, bounceHistory, rec->placement, r);
      });
      const auto placing = std::chrono::steady_clock::now();
      placeSeeds(live, rec->placement, rec->seeds);
      run.times.add("record seeds", secondsSince(placing));
      run("record seeds", live, [&](IndexRange r) {
        stageRecordSeeds(ctx, w.paths, w.slots[cur], w.hits, w.shadowRays, bounceHistory, rec->placement, rec->seeds, r);
      });
    }
    const auto start = std::chrono::steady_clock::now();
    bounceHistory.base += live;
    const size_t kept =
        stageCompact(w.slots[cur], w.rays[cur], w.slots[1 - cur], w.rays[1 - cur], live, run.grain(live), w.ended.data());
    // The paths that ended: their radiance is final; their ids start the next samples.
    for (size_t i = 0; i < live - kept; ++i) {
      const uint32_t id = w.ended[i];
      const size_t at = w.paths.runIndex[id] - outFirst;
      out.pixel[at] = w.paths.pixel[id];
      out.x[at] = w.paths.filmX[id], out.y[at] = w.paths.filmY[id];
      out.r[at] = w.paths.radianceR[id], out.g[at] = w.paths.radianceG[id], out.b[at] = w.paths.radianceB[id];
    }
    w.freeIds.insert(w.freeIds.end(), w.ended.begin(), w.ended.begin() + ptrdiff_t(live - kept));
    run.times.add("compact", secondsSince(start));
    live = kept;
    cur = 1 - cur;
  }
}
}  // namespace

struct PathTracerScratch::Impl {
  PathWavefront wavefront;
  BatchRadiance radiance;
  VertexQueue history;
  SeedPlacement placement;
};
PathTracerScratch::PathTracerScratch() : impl(std::make_unique<Impl>()) {}
PathTracerScratch::~PathTracerScratch() = default;

uint64_t traceSeedsInline(const Tracer& tracer, const StageContext& ctx, const PathSampleSet& samples, SeedStore& seeds,
                          PathTracerScratch& scratch, StageTimes& times) {
  std::atomic<uint64_t> rays{0};
  if (samples.count == 0) return 0;
  SeedRecording rec{seeds, scratch.impl->history, scratch.impl->placement};
  scratch.impl->radiance.resize(samples.count);
  traceSamples(tracer, ctx, samples, 0, samples.count, samples.count, scratch.impl->wavefront, StageRunner{false, times},
               scratch.impl->radiance, 0, &rec, rays);
  return rays;
}

uint64_t traceReplayedSamples(const Tracer& tracer, const StageContext& ctx, const uint32_t* chains, size_t n,
                              PathTracerScratch& scratch, StageTimes& times, float* filmX, float* filmY, Color* radiance) {
  std::atomic<uint64_t> rays{0};
  if (n == 0) return 0;
  const PathSampleSet samples{n, [chains](size_t k, uint32_t& pixel, uint32_t& sample) {
                                pixel = 0;  // unused: the film position is the chain's
                                sample = chains[k];
                              }};
  BatchRadiance& out = scratch.impl->radiance;
  out.resize(n);
  traceSamples(tracer, ctx, samples, 0, n, std::min(n, kTaskQueue), scratch.impl->wavefront, StageRunner{false, times}, out,
               0, nullptr, rays);
  for (size_t k = 0; k < n; ++k) {
    filmX[k] = out.x[k], filmY[k] = out.y[k];
    radiance[k] = out.at(k);
  }
  return rays;
}

void deliverBatch(const PathTraceOutput& out, size_t done, size_t total) {
  if (out.seeds && out.seedSink) {
    out.seedSink(*out.seeds);
    out.seeds->clear();
  }
  if (out.progress) out.progress(double(done) / double(total));
}

void addRunCounts(RenderStats& stats, uint64_t samples, uint64_t rays, uint64_t invalid) {
  stats.samples += samples;
  stats.rays += rays;
  stats.invalidSamples += invalid;
}

bool tracePathSamples(const RenderSetup& setup, const PathSampleSet& samples, const PathTraceOutput& out,
                      RenderStats& stats) {
  const size_t total = samples.count;
  const double threads = double(setup.pool.threads());
  std::atomic<uint64_t> rayCount{0};
  uint64_t invalid = 0;
  BatchRadiance batch;
  PathTracerScratch ownScratch;                          // seed recording, when the caller keeps none
  PathTracerScratch& recording = out.scratch ? *out.scratch : ownScratch;
  PerThread<PathWavefront> local;                        // rendering: one per thread
  std::mutex timesMutex;

  bool complete = true;
  const size_t batchPaths = out.seeds ? kSeedBatchPaths : kBatchPaths;
  for (size_t first = 0; first < total; first += batchPaths) {
    if (stopRequested(out.stop)) {
      complete = false;
      break;
    }
    const size_t n = std::min(batchPaths, total - first);
    batch.resize(n);
    if (out.seeds) {
      SeedRecording rec{*out.seeds, recording.impl->history, recording.impl->placement};
      traceSamples(setup.tracer, setup.ctx, samples, first, n, n, recording.impl->wavefront,
                   StageRunner{true, stats.stages}, batch, first, &rec, rayCount);
    } else {
      // One task per chunk of samples, each on its thread's own wavefront.
      forEachRange("path chunks", (n + kChunkSamples - 1) / kChunkSamples, 1, [&](IndexRange chunks) {
        for (size_t c = chunks.begin; c < chunks.end; ++c) {
          StageTimes times;
          const size_t begin = first + c * kChunkSamples, count = std::min(kChunkSamples, first + n - begin);
          traceSamples(setup.tracer, setup.ctx, samples, begin, count, kTaskQueue, local.local(),
                       StageRunner{false, times}, batch, first, nullptr, rayCount);
          // Stage times of the tasks, in seconds of the whole pool (thread time / threads).
          std::lock_guard<std::mutex> lock(timesMutex);
          for (const auto& [stage, seconds] : times.all()) stats.stages.add(stage, seconds / threads);
        }
      });
    }

    for (size_t i = 0; i < n; ++i) {
      const Color L = batch.at(i);
      invalid += !isFinite(L);
      if (out.film) out.film->addIfFinite(batch.pixel[i], L);
    }
    if (out.splat) {
      auto start = std::chrono::steady_clock::now();
      out.splat->addSamples(batch.x.data(), batch.y.data(), batch.r.data(), batch.g.data(), batch.b.data(), n);
      stats.stages.add("splat", secondsSince(start));
    }
    deliverBatch(out, first + n, total);
  }
  addRunCounts(stats, total, rayCount, invalid);
  return complete;
}

RgbImage renderPath(const Scene& scene, const RenderSettings& settings, RenderStats& stats, FilmMode film) {
  RenderSetup setup(scene, settings, film);
  std::optional<SplatFilm> splat;
  if (setup.filmMode != FilmMode::Fis) splat.emplace(setup.filter, settings.width, settings.height);
  SamplePassHooks passes;
  if (splat) setFilmStateHooks(passes, *splat, stats);
  else setFilmStateHooks(passes, setup.film, stats);
  PathTracerScratch scratch;
  passes.run = [&](int first, int end, const std::function<void(double)>& progress) {
    const PathTraceOutput out{splat ? nullptr : &setup.film, splat ? &*splat : nullptr, settings.seeds, settings.seedSink,
                              progress, settings.stop, &scratch};
    return tracePathSamples(setup, passSamples(setup.order, first, end, settings.share), out, stats);
  };
  passes.image = [&](int done) {
    return splat ? splat->resolve(setup.filmMode, double(done)) : setup.film.resolve(double(done));
  };
  return renderInSamplePasses(settings, setup.order.size(), stats, passes);
}

IntegratorModule pathModule() {
  IntegratorModule m;
  m.name = "path";
  m.description = "the wavefront path tracer (next-event estimation, MIS, Russian roulette); the default";
  m.samplePasses = true;
  // The only integrator that may splat its samples (film_splat.h); the others' films are FIS.
  m.options = {choiceOption<FilmMode>(
      "film",
      "fis (filter importance sampling: each sample counts in its own pixel), splat (samples uniform in the pixel, "
      "splatted over the filter, normalized by the weights: Mitsuba's and pbrt-v3's), splat-unbiased (normalized by "
      "the expected weights) or auto (per filter: docs/film-splatting.md)",
      {{"auto", FilmMode::Auto}, {"fis", FilmMode::Fis}, {"splat", FilmMode::Splat}, {"splat-unbiased", FilmMode::SplatUnbiased}},
      [](auto& s) -> auto& { return s.film; })};
  m.validate = [](const RenderSettings&) {};
  m.render = [](const Scene& scene, const RenderSettings& s, RenderStats& stats) {
    return renderPath(scene, s, stats, filmModeFor(s.film, s.filter));
  };
  return m;
}

}  // namespace erpt
