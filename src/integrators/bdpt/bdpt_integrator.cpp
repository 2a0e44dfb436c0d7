// `--integrator bdpt`: bidirectional path tracing over wavefronts (Veach's thesis, ch. 10).
//
// Each task of the thread pool takes a chunk of samples (kChunkSamples) and runs them through
// its own queues: every sample's light subpath is walked bounce by bounce over the live walks
// (intersect as a ray stream, then extend), then its camera subpath likewise, then every
// strategy (s, t) of the two is formed at once and the connections' shadow rays are traced as
// one occlusion stream. A sample's camera strategies add up at its film position; light
// tracing (t = 1) splats at the film positions it reaches. The film (film_splat.h, unbiased
// splatting: camera samples uniform in their pixel) adds the camera samples in sample order and
// then each chunk's light-tracing splats in chunk order, so the image does not depend on the
// thread count.
#include "integrators/bdpt/bdpt_integrator.h"

#include <atomic>
#include <chrono>
#include <mutex>

#include "core/parallel.h"
#include "erpt/bdpt_settings.h"
#include "models/film_splat.h"
#include "render_setup.h"
#include "sample_passes.h"
#include "integrators/bdpt/bdpt_wavefront.h"

namespace erpt {

namespace {
constexpr size_t kBatchSamples = 1 << 16;  // samples that reach the film together
constexpr size_t kChunkSamples = 2048;     // one task's share of a batch

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Splats of one chunk: its samples' camera strategies (one per sample, at its film position)
// and its light tracing.
struct ChunkSplats {
  std::vector<float> x, y, r, g, b;
  void clear() {
    for (auto* v : {&x, &y, &r, &g, &b}) v->clear();
  }
  void add(float fx, float fy, Color c) {
    x.push_back(fx), y.push_back(fy), r.push_back(c.x), g.push_back(c.y), b.push_back(c.z);
  }
  void append(const ChunkSplats& o) {
    for (auto [to, from] : {std::pair{&x, &o.x}, {&y, &o.y}, {&r, &o.r}, {&g, &o.g}, {&b, &o.b}})
      to->insert(to->end(), from->begin(), from->end());
  }
};

// What one chunk hands to the film and to ERPT: its samples' camera strategies (one splat per
// sample at its film position) and light tracing, and, when asked, its contributions as seeds.
struct ChunkOutput {
  ChunkSplats camera, lightTracing;
  SeedStore seeds;
};

// Samples [begin, begin + n) of `samples` through wavefront `w` into `out` (in sample order).
// Returns the rays traced.
uint64_t traceChunk(const Tracer& tracer, const BdptContext& ctx, const PathSampleSet& samples, size_t begin, size_t n,
                    bool recordSeeds, BdptWavefront& w, ChunkOutput& out, uint64_t& invalid, StageTimes& times) {
  w.prepare(n);
  for (size_t j = 0; j < n; ++j) samples.at(begin + j, w.paths.pixel[j], w.paths.sample[j]);
  uint64_t rays = walkSubpaths(tracer, ctx, BdptSide::Light, w, n, times);
  rays += walkSubpaths(tracer, ctx, BdptSide::Camera, w, n, times);

  rays += connectSubpaths(tracer, ctx, w, n, times);
  const size_t m = w.connections.size();
  auto start = std::chrono::steady_clock::now();
  for (size_t c = 0; c < m; ++c) {
    if (!(w.shadowRays.tfar[c] >= 0)) continue;  // occluded
    const Color value = w.connections.valueAt(c);
    if (w.connections.toCamera[c]) out.lightTracing.add(w.connections.filmX[c], w.connections.filmY[c], value);
    else w.radiance[w.connections.sample[c]] += value;
  }
  for (size_t j = 0; j < n; ++j) {
    const Color L = w.radiance[j];
    if (!isFinite(L)) {
      ++invalid;
      continue;
    }
    out.camera.add(w.paths.filmX[j], w.paths.filmY[j], L);
  }
  times.add("resolve", secondsSince(start));
  if (recordSeeds) {
    start = std::chrono::steady_clock::now();
    stageBdptRecordSeeds(ctx, w.paths, w.scratch, w.connections, w.shadowRays, m, begin, out.seeds);
    times.add("record seeds", secondsSince(start));
  }
  return rays;
}
}  // namespace

bool traceBdptSamples(const RenderSetup& setup, int height, const BdptSettings& own, const PathSampleSet& samples,
                      const PathTraceOutput& out, RenderStats& stats) {
  const BdptContext ctx{setup.ctx, height, own.onlyS, own.onlyT, own.unweighted};
  const size_t total = samples.count;
  const double threads = double(setup.pool.threads());
  std::atomic<uint64_t> rayCount{0}, invalid{0};
  PerThread<BdptWavefront> local;
  std::mutex timesMutex;
  std::vector<ChunkOutput> chunks;
  ChunkSplats batchCamera;
  bool complete = true;
  for (size_t first = 0; first < total; first += kBatchSamples) {
    if (stopRequested(out.stop)) {
      complete = false;
      break;
    }
    const size_t n = std::min(kBatchSamples, total - first);
    const size_t chunkCount = (n + kChunkSamples - 1) / kChunkSamples;
    chunks.resize(chunkCount);
    forEachRange("bdpt chunks", chunkCount, 1, [&](IndexRange range) {
      for (size_t c = range.begin; c < range.end; ++c) {
        StageTimes times;
        const size_t begin = first + c * kChunkSamples, count = std::min(kChunkSamples, first + n - begin);
        uint64_t bad = 0;
        chunks[c].camera.clear();
        chunks[c].lightTracing.clear();
        chunks[c].seeds.clear();
        rayCount += traceChunk(setup.tracer, ctx, samples, begin, count, out.seeds != nullptr, local.local(), chunks[c],
                               bad, times);
        invalid += bad;
        std::lock_guard<std::mutex> lock(timesMutex);
        for (const auto& [stage, seconds] : times.all()) stats.stages.add(stage, seconds / threads);
      }
    });
    const auto start = std::chrono::steady_clock::now();
    if (out.splat) {  // the camera samples, then light tracing, each in chunk order
      ChunkSplats& all = batchCamera;
      all.clear();
      for (const ChunkOutput& c : chunks) all.append(c.camera);
      out.splat->addSamples(all.x.data(), all.y.data(), all.r.data(), all.g.data(), all.b.data(), all.x.size());
      for (const ChunkOutput& c : chunks) {
        const ChunkSplats& l = c.lightTracing;
        out.splat->addScattered(l.x.data(), l.y.data(), l.r.data(), l.g.data(), l.b.data(), l.x.size());
      }
    }
    stats.stages.add("splat", secondsSince(start));
    if (out.seeds)
      for (const ChunkOutput& c : chunks) out.seeds->appendAll(c.seeds);
    deliverBatch(out, first + n, total);
  }
  addRunCounts(stats, total, rayCount, invalid);
  return complete;
}

RgbImage renderBdpt(const Scene& scene, const RenderSettings& settings, RenderStats& stats) {
  RenderSetup setup(scene, settings, FilmMode::SplatUnbiased);
  SplatFilm film(setup.filter, settings.width, settings.height);
  SamplePassHooks passes;
  setFilmStateHooks(passes, film, stats);
  passes.run = [&](int first, int end, const std::function<void(double)>& progress) {
    const PathTraceOutput out{nullptr, &film, settings.seeds, settings.seedSink, progress, settings.stop};
    return traceBdptSamples(setup, settings.height, bdptOf(settings), passSamples(setup.order, first, end, settings.share),
                            out, stats);
  };
  passes.image = [&](int done) { return film.resolve(FilmMode::SplatUnbiased, double(done)); };
  return renderInSamplePasses(settings, setup.order.size(), stats, passes);
}

IntegratorModule bdptModule() {
  IntegratorModule m;
  m.name = "bdpt";
  m.description = "bidirectional path tracing: every strategy (s, t) with MIS (power heuristic), light tracing splatted";
  m.samplePasses = true;
  const auto someStrategy = [](const RenderSettings& s) {
    return bdptOf(s).onlyS < 0 && bdptOf(s).onlyT < 0 ? std::string("applies with --bdpt-s or --bdpt-t only")
                                                       : std::string();
  };
  m.options = {
      integerOption("bdpt-s", "render only the strategies with this many light vertices (-1: all)", -1, 1 << 20,
                    [](auto& s) -> auto& { return bdptOf(s).onlyS; }),
      integerOption("bdpt-t", "render only the strategies with this many camera vertices (-1: all)", -1, 1 << 20,
                    [](auto& s) -> auto& { return bdptOf(s).onlyT; }),
      onlyWhen(choiceOption<bool>("bdpt-weights",
                                  "mis (each strategy's MIS weight) or none (the chosen strategies unweighted: each "
                                  "alone estimates every path it can make)",
                                  {{"mis", false}, {"none", true}},
                                  [](auto& s) -> auto& { return bdptOf(s).unweighted; }),
               someStrategy)};
  m.validate = [](const RenderSettings& s) {
    if (bdptOf(s).onlyT == 0) throw UsageError("--bdpt-t must be -1 or at least 1: the camera is never hit (t = 0)");
  };
  m.render = [](const Scene& scene, const RenderSettings& s, RenderStats& stats) { return renderBdpt(scene, s, stats); };
  return m;
}

}  // namespace erpt
