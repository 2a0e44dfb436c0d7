// Sample passes, stopping early and resuming (RenderSettings::stop / onPasses / resume;
// docs/long-renders.md): a render resumed from any of its states, any number of times, gives
// the bit-identical image of the uninterrupted render, and a stopped render is an unbiased
// image at the passes it completed.
#include <gtest/gtest.h>

#include <condition_variable>
#include <cstring>
#include <mutex>
#include <thread>

#include "erpt/erpt_settings.h"
#include "erpt/pmc_settings.h"
#include "erpt/render.h"
#include "erpt/scene_loader.h"
#include "support/block_bias.h"
#include "support/image_stats.h"
#include "support/test_support.h"

namespace erpt {
namespace {

Scene defaultScene() { return loadScene(test::sourceDir() + "/scenes/default/scene.xml"); }

bool sameBits(const RgbImage& a, const RgbImage& b) {
  return a.width == b.width && a.height == b.height && a.pixels.size() == b.pixels.size() &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(Color)) == 0;
}

struct Case {
  const char* name;
  RenderSettings settings;
};

std::vector<Case> cases() {
  RenderSettings base;
  base.width = 64, base.height = 32;  // 2048 pixels: passes run in groups of 4
  base.passGroupSamples = 8192;
  base.spp = 12;
  base.seed = 7;
  base.filterSet = true;
  base.filter = FilterKind::Box;
  std::vector<Case> out;
  out.push_back({"path box", base});
  RenderSettings tent = base;
  tent.filter = FilterKind::Tent;
  tent.film = FilmMode::Splat;
  out.push_back({"path tent splat", tent});
  RenderSettings unbiased = tent;
  unbiased.film = FilmMode::SplatUnbiased;
  out.push_back({"path tent splat-unbiased", unbiased});
  RenderSettings direct = base;
  direct.integrator = "direct";
  out.push_back({"direct", direct});
  RenderSettings bdpt = tent;
  bdpt.integrator = "bdpt";
  out.push_back({"bdpt tent", bdpt});
  RenderSettings erpt = base;
  erpt.integrator = "erpt";
  erpt.width = erpt.height = 48;  // groups of 3 passes
  erpt.spp = 9;
  chainOf(erpt).mutationsPerPixel = 16;
  erptOf(erpt).chainLength = 20;
  chainOf(erpt).directSamples = 4;
  chainOf(erpt).pmFilterRadius = 2;
  out.push_back({"erpt, direct pass, pm filter", erpt});
  RenderSettings consecutive = erpt;
  chainOf(consecutive).directSamples = -1;
  chainOf(consecutive).pmFilterRadius = -1;
  chainOf(consecutive).maxConsecutive = 5;
  chainOf(consecutive).expectedDeposit = true;
  out.push_back({"erpt, expected deposits, consecutive filter", consecutive});
  RenderSettings pmc = erpt;  // 48x48, groups of 3 passes: the population runs once per group
  pmc.integrator = "pmc-er";
  pmcOf(pmc).population = 200;
  pmcOf(pmc).mutationsPerMember = 4;
  out.push_back({"pmc-er, region adaptation, direct pass, pm filter", pmc});
  RenderSettings balance = pmc;
  pmcOf(balance).flow = PmcFlow::Balance;
  pmcOf(balance).adapt = PmcAdapt::Member;
  chainOf(balance).directSamples = -1;
  chainOf(balance).pmFilterRadius = -1;
  out.push_back({"pmc-er, balance flow, member adaptation", balance});
  return out;
}

// Every state a render passes through, in order.
std::vector<RenderState> renderCollectingStates(const Scene& scene, RenderSettings s, RgbImage& image,
                                                const RenderState* resume = nullptr) {
  std::vector<RenderState> states;
  s.resume = resume;
  s.onPasses = [&](const RenderState& state, const std::function<RgbImage()>&) { states.push_back(state); };
  RenderStats stats;
  image = render(scene, s, stats);
  EXPECT_FALSE(stats.partial);
  EXPECT_EQ(stats.spp, s.spp);
  return states;
}

TEST(Resume, ResumedRendersAreBitIdenticalToUninterruptedOnes) {
  const Scene scene = defaultScene();
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    RenderStats plainStats;
    const RgbImage plain = render(scene, c.settings, plainStats);  // no state kept at all
    RgbImage full;
    const std::vector<RenderState> states = renderCollectingStates(scene, c.settings, full);
    ASSERT_TRUE(sameBits(plain, full));
    ASSERT_GE(states.size(), 3u);  // the start, at least one group in the middle, the end
    EXPECT_EQ(states.front().passesDone, 0);
    EXPECT_EQ(states.back().passesDone, c.settings.spp);
    // From the middle state; then from a state of that resumed render (twice interrupted).
    const RenderState& middle = states[states.size() / 2];
    RgbImage once;
    const std::vector<RenderState> later = renderCollectingStates(scene, c.settings, once, &middle);
    EXPECT_TRUE(sameBits(once, full)) << "resumed after " << middle.passesDone << " passes";
    ASSERT_GE(later.size(), 2u);
    EXPECT_EQ(later.front().bytes, middle.bytes);
    RgbImage twice;
    renderCollectingStates(scene, c.settings, twice, &later[1]);
    EXPECT_TRUE(sameBits(twice, full)) << "resumed again after " << later[1].passesDone << " passes";
    // The same states at another thread count.
    RenderSettings one = c.settings;
    one.threads = 1;
    RgbImage single;
    renderCollectingStates(scene, one, single, &middle);
    EXPECT_TRUE(sameBits(single, full)) << "resumed on one thread";
  }
}

// Stopped part-way through a group of passes (from inside a batch's progress report), the
// render falls back to its last completed group: the stopped image is that state's image, and
// resuming from that state ends bit-identical to the uninterrupted render.
TEST(Resume, AStopInsideAGroupFallsBackToTheLastGroupAndResumesFromIt) {
  const Scene scene = defaultScene();
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    RgbImage full;
    renderCollectingStates(scene, c.settings, full);
    std::atomic<bool> stop{false};
    RenderSettings s = c.settings;
    s.stop = &stop;
    RenderState last;
    RgbImage lastImage;
    s.onPasses = [&](const RenderState& state, const std::function<RgbImage()>& image) {
      last = state;
      if (state.passesDone > 0) lastImage = image();
    };
    // Past the first group, the first progress report stops the render.
    s.progress = [&](double f) {
      if (last.passesDone > 0 && f > double(last.passesDone) / s.spp) stop = true;
    };
    RenderStats stats;
    const RgbImage stopped = render(scene, s, stats);
    ASSERT_TRUE(stats.partial);
    ASSERT_GT(stats.spp, 0);
    ASSERT_LT(stats.spp, s.spp);
    EXPECT_EQ(stats.spp, last.passesDone);
    EXPECT_TRUE(sameBits(stopped, lastImage));
    RgbImage resumed;
    renderCollectingStates(scene, c.settings, resumed, &last);
    EXPECT_TRUE(sameBits(resumed, full));
  }
}

TEST(Resume, AStateOfOtherSettingsIsRefused) {
  const Scene scene = defaultScene();
  RenderSettings s = cases()[0].settings;
  RgbImage image;
  const std::vector<RenderState> states = renderCollectingStates(scene, s, image);
  RenderSettings other = s;
  other.width = 128;  // another film size: the film sums do not fit
  RenderStats stats;
  other.resume = &states[1];
  EXPECT_THROW(render(scene, other, stats), std::runtime_error);
  RenderState cut = states[1];
  cut.bytes.resize(cut.bytes.size() / 2);
  s.resume = &cut;
  EXPECT_THROW(render(scene, s, stats), std::runtime_error);
  RenderState late = states[1];
  late.passesDone = s.spp + 1;
  s.resume = &late;
  EXPECT_THROW(render(scene, s, stats), std::runtime_error);
  RenderSettings pmc = s;  // a path tracer's state given to PMC-ER
  pmc.integrator = "pmc-er";
  pmc.resume = &states[1];
  EXPECT_THROW(render(scene, pmc, stats), std::runtime_error);
}

// A render stopped after some of its passes is an unbiased render at those passes: block by
// block against long path-traced renders (z-scores over independent runs), for the path tracer
// and ERPT. A stopped render normalised by the requested spp would be 4x too dark here; ERPT
// chains cut off at the stop would lose energy.
void expectStoppedRendersAreUnbiased(const Scene& scene, RenderSettings s, int stopAfter, int runs, uint64_t seed) {
  std::atomic<bool> stop{false};
  int stopped = 0;
  s.stop = &stop;
  s.onPasses = [&](const RenderState& state, const std::function<RgbImage()>&) {
    if (state.passesDone >= stopAfter) stop = true, ++stopped;
  };
  test::BlockTestOptions options;
  options.beforeEachRun = [&] { stop = false; };
  test::expectMatchesPathTracerBlockByBlock(scene, s, runs, seed, options);
  EXPECT_EQ(stopped, runs);
}

TEST(StatisticalResume, StoppedPathRenderIsUnbiasedAtThePassesDone) {
  RenderSettings s;
  s.spp = 128;  // 64x64: groups of 32 passes; stopped after the first
  expectStoppedRendersAreUnbiased(defaultScene(), s, 32, 16, 101);
}

TEST(StatisticalErpt, StoppedRenderIsUnbiasedAtThePassesDone) {
  RenderSettings s;
  s.integrator = "erpt";
  s.spp = 32;
  s.passGroupSamples = 32768;  // 64x64: groups of 8 passes; stopped after 2 groups
  chainOf(s).mutationsPerPixel = 400;  // per pixel of the 32 spp asked for: about 200 run
  expectStoppedRendersAreUnbiased(defaultScene(), s, 16, 16, 202);
}

// PMC-ER runs its population once per group of passes (to its end, so that no member is in
// flight between groups): a render of two groups against the path tracer, block by block.
// Equal deposition, region adaptation, every path by PMC-ER; a population of 1000 makes some
// 45 iterations per group here. (This is also the suite's whole-render test of that
// configuration on the default scene: tests/integrators/pmc_er/pmc_render_test.cpp has the others.) A stopped
// PMC-ER render is the image of the groups it completed (Resume.AStopInsideAGroup... above);
// that a subset of the passes is unbiased, StatisticalResume.StoppedPathRender shows for the
// camera samples PMC-ER's pool shares. It is not stopped here: with 12 runs of this scene a
// render of 8 of 16 passes sees heavy tails (the path tracer alone, 8 of 16 passes of seeds
// 5000-5011: worst block |z| 4.2; PMC-ER 6.1; with 32 runs PMC-ER gives docs/long-renders.md's
// figures).
TEST(StatisticalPmc, SeveralGroupsOfPassesMatchPathTracerBlockByBlock) {
  RenderSettings s;
  s.integrator = "pmc-er";
  s.spp = 8;
  s.passGroupSamples = 16384;  // 64x64: two groups of 4 passes
  pmcOf(s).population = 1000;
  chainOf(s).directSamples = -1;
  test::expectMatchesPathTracerBlockByBlock(defaultScene(), s, 12, 5000);
}

}  // namespace
}  // namespace erpt

namespace erpt {
namespace {

// Two ranks of a split render in one process (threads), with the rank-order sum MPI gives
// them (src/cli/process_group.cpp): what `mpirun -n 2` runs, under the sanitizers too.
class InProcessRanks {
 public:
  explicit InProcessRanks(int ranks) : ranks_(ranks), inputs_(size_t(ranks)) {}
  RenderShare share(int rank) {
    RenderShare s;
    s.rank = rank;
    s.ranks = ranks_;
    s.sumAcrossRanks = [this, rank](std::vector<double>& v) { sum(rank, v); };
    return s;
  }

 private:
  void sum(int rank, std::vector<double>& v) {
    std::unique_lock<std::mutex> lock(m_);
    const uint64_t round = round_;
    inputs_[size_t(rank)] = &v;
    if (++arrived_ == ranks_) {
      result_.assign(v.size(), 0.0);
      for (const std::vector<double>* in : inputs_)  // rank order
        for (size_t i = 0; i < in->size(); ++i) result_[i] += (*in)[i];
      for (std::vector<double>* in : inputs_) *in = result_;
      arrived_ = 0;
      ++round_;
      cv_.notify_all();
    } else {
      cv_.wait(lock, [&] { return round_ != round; });
    }
  }
  int ranks_, arrived_ = 0;
  uint64_t round_ = 0;
  std::vector<std::vector<double>*> inputs_;
  std::vector<double> result_;
  std::mutex m_;
  std::condition_variable cv_;
};

std::vector<RgbImage> renderSplit(const Scene& scene, const RenderSettings& base, int ranks) {
  InProcessRanks group(ranks);
  std::vector<RgbImage> images(static_cast<size_t>(ranks));
  std::vector<std::thread> threads;
  for (int r = 0; r < ranks; ++r)
    threads.emplace_back([&, r] {
      RenderSettings s = base;
      s.share = group.share(r);
      RenderStats stats;
      images[size_t(r)] = render(scene, s, stats);
      EXPECT_EQ(stats.spp, base.spp);
    });
  for (std::thread& t : threads) t.join();
  return images;
}

TEST(Resume, SplitRendersAddUpToTheWholeRender) {
  const Scene scene = defaultScene();
  RenderSettings s;
  s.width = s.height = 32;
  s.spp = 9;  // not a multiple of the ranks: rank 0 renders 5 passes, rank 1 four
  s.threads = 1;
  s.seed = 5;
  s.filterSet = true;
  s.filter = FilterKind::Tent;  // splatting: weights are summed too
  pmcOf(s).population = 200;
  for (const char* integrator : {"path", "direct", "erpt", "pmc-er", "bdpt"}) {
    SCOPED_TRACE(integrator);
    s.integrator = integrator;
    chainOf(s).directSamples = 4;
    chainOf(s).pmFilterRadius = 1;  // the tally is summed too
    const std::vector<RgbImage> split = renderSplit(scene, s, 2);
    EXPECT_TRUE(sameBits(split[0], split[1]));  // every rank holds the whole image
    EXPECT_TRUE(sameBits(split[0], renderSplit(scene, s, 2)[0]));  // and the same every run
    RenderStats stats;
    const RgbImage whole = render(scene, s, stats);
    double worst = 0, sum = 0, sumWhole = 0;
    for (size_t i = 0; i < whole.pixels.size(); ++i)
      for (int c = 0; c < 3; ++c) {
        worst = std::max(worst, std::abs(double(split[0].pixels[i][c]) - whole.pixels[i][c]) / (whole.pixels[i][c] + 1e-3));
        sum += split[0].pixels[i][c], sumWhole += whole.pixels[i][c];
      }
    if (std::string(integrator) == "erpt" || std::string(integrator) == "pmc-er")
      EXPECT_NEAR(sum / sumWhole, 1.0, 0.05);  // other chains, same seeds: the same image up to noise
    else
      EXPECT_LT(worst, 1e-5);  // the same samples, added in another order
  }
}

}  // namespace
}  // namespace erpt
