#include "sample_passes.h"

#include <algorithm>

namespace erpt {

namespace {
// A group of passes has at least this many samples when the image is small (one batch of the
// path tracer's wavefront: fewer would leave threads idle).
constexpr size_t kGroupSamples = 1 << 17;

int passesPerGroup(size_t pixels, size_t groupSamples) {
  return int(std::clamp<size_t>((groupSamples ? groupSamples : kGroupSamples) / std::max<size_t>(pixels, 1), 1, 1 << 20));
}
}  // namespace

PathSampleSet passSamples(const std::vector<uint32_t>& order, int first, int end, const RenderShare& share) {
  const size_t pixels = order.size();
  const uint32_t rank = uint32_t(share.rank), ranks = uint32_t(std::max(1, share.ranks));
  return PathSampleSet{pixels * size_t(end - first),
                       [&order, pixels, first, rank, ranks](size_t k, uint32_t& pixel, uint32_t& sample) {
                         pixel = order[k % pixels];
                         sample = rank + ranks * (uint32_t(first) + uint32_t(k / pixels));
                       }};
}

void sumCounters(const RenderShare& share, std::initializer_list<uint64_t*> counters) {
  std::vector<double> values;
  for (const uint64_t* c : counters) values.push_back(double(*c));
  share.sumAcrossRanks(values);
  size_t k = 0;
  for (uint64_t* c : counters) *c = uint64_t(values[k++]);
}

int passesOfRank(int total, const RenderShare& share) {
  if (!share.split()) return total;
  return share.rank < total ? (total - share.rank + share.ranks - 1) / share.ranks : 0;
}

RgbImage renderInSamplePasses(const RenderSettings& s, size_t pixels, RenderStats& stats, const SamplePassHooks& hooks) {
  const int total = passesOfRank(s.spp, s.share);
  // The state is kept only when someone can use it: a stop rolls back to it, onPasses sees it.
  // After the last pass only onPasses can (nothing is left to roll back).
  const bool keepState = s.stop || s.onPasses;
  RenderState state;
  auto save = [&](int done) {
    state.passesDone = done;
    if (!keepState || (done == total && !s.onPasses)) return;
    ByteWriter w(std::move(state.bytes));
    w.putString(s.integrator);
    hooks.save(w);
    state.bytes = w.take();
  };
  auto boundary = [&]() {
    if (s.onPasses) s.onPasses(state, [&] { return hooks.image(state.passesDone); });
  };
  int done = 0;
  if (s.resume) {
    if (s.resume->passesDone < 0 || s.resume->passesDone > total)
      throw std::runtime_error("checkpoint holds " + std::to_string(s.resume->passesDone) + " passes of " +
                               std::to_string(total));
    ByteReader r(s.resume->bytes);
    const std::string integrator = r.getString(64);
    if (integrator != s.integrator)
      throw std::runtime_error("the state is of a render with --integrator " + integrator + ", not " + s.integrator);
    hooks.load(r);
    r.expectEnd();
    done = s.resume->passesDone;
    state = *s.resume;
  } else {
    save(0);
  }
  boundary();
  const int group = passesPerGroup(pixels, s.passGroupSamples);
  while (done < total && !stopRequested(s.stop)) {
    const int end = std::min(total, done + group);
    const int first = done;
    auto progress = [&](double f) {
      if (s.progress) s.progress((double(first) + f * double(end - first)) / double(total));
    };
    if (!hooks.run(first, end, progress)) {
      // Before any group completed, the chain integrators keep the stopped group's work rather
      // than return nothing; after one, the roll-back gives an unbiased image of its passes.
      if (hooks.stoppedImage && done == 0 && !s.share.split()) {
        stats.partial = true;
        stats.spp = done;
        return hooks.stoppedImage(done, end, stats);
      }
      ByteReader r(state.bytes);
      r.getString(64);  // the integrator's name
      hooks.load(r);
      break;
    }
    done = end;
    save(done);
    boundary();
  }
  stats.partial = done < total;
  if (s.share.split()) {
    // Every rank gets here (a stop ends the loop, never skips this): the same collective calls.
    std::vector<double> counts{double(done), double(stats.partial)};
    s.share.sumAcrossRanks(counts);
    done = int(counts[0]);
    stats.partial = counts[1] > 0;
    hooks.reduce(s.share);
  }
  stats.spp = done;
  if (done > 0) return hooks.image(done);
  RgbImage none;  // stopped before the first pass completed: nothing to show
  none.width = s.width, none.height = s.height;
  none.pixels.assign(size_t(s.width) * size_t(s.height), Color(0.0f));
  return none;
}

}  // namespace erpt
