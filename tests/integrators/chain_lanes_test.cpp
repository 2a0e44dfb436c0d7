// ERPT's chain lanes (chain_lanes.h): several chain queues stepped at once by different
// threads, depositing into an ExactFilm. The image must not depend on how many lanes ran, which
// lane ran a chain, or in what order the deposits landed.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <random>
#include <vector>

#include "integrators/chain_lanes.h"
#include "models/exact_film.h"
#include "core/parallel.h"
#include "support/erpt_world.h"
#include "support/image_stats.h"
#include "support/test_support.h"

namespace erpt {
namespace {

using test::ErptWorld;

std::string defaultScene() { return test::sourceDir() + "/scenes/default/scene.xml"; }

// Integer sums: the same bits in any order of the adds, and within the rounding of the unit of
// the double sum of the same values.
TEST(ExactFilm, SumsDoNotDependOnTheOrderOfTheAdds) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> value(0, 1), weight(0, 1);
  struct Add {
    uint32_t pixel;
    Color c;
    float w;
  };
  std::vector<Add> adds;
  // Magnitudes over 9 decades, as a tent filter's edge weights and bright deposits give.
  for (int i = 0; i < 20000; ++i) {
    const float scale = std::pow(10.0f, float(int(rng() % 10)) - 5);
    adds.push_back({uint32_t(rng() % 4), Color(value(rng), value(rng), value(rng)) * scale, weight(rng)});
  }
  const double unit = std::ldexp(1.0, -24);
  ExactFilm forward(2, 2, unit, false), backward(2, 2, unit, true);
  std::vector<double> sums(12, 0.0);
  for (const Add& a : adds) {
    ASSERT_TRUE(forward.fits(a.c));
    forward.add(a.pixel, a.c, a.w);
    sums[3 * a.pixel] += double(a.c.x) * a.w;
  }
  for (size_t i = adds.size(); i-- > 0;) backward.add(adds[i].pixel, adds[i].c, adds[i].w);
  RgbImage f{2, 2, std::vector<Color>(4), {}}, b{2, 2, std::vector<Color>(4), {}};
  forward.addTo(f, 1.0);
  backward.addTo(b, 1.0);
  test::expectBitIdentical(f, b);
  // What a double film does with the same adds: its sums depend on the order.
  Film df(2, 2), db(2, 2);
  for (const Add& a : adds) df.add(a.pixel, a.c * a.w);
  for (size_t i = adds.size(); i-- > 0;) db.add(adds[i].pixel, adds[i].c * adds[i].w);
  ByteWriter sf, sb;
  df.save(sf), db.save(sb);
  EXPECT_NE(sf.bytes(), sb.bytes());
  // Each add rounds by at most half a unit.
  for (int p = 0; p < 4; ++p) EXPECT_NEAR(f.pixels[size_t(p)].x, sums[size_t(3 * p)], 1e-6 * sums[size_t(3 * p)] + 1e4 * unit);
}

// Chain lanes' own films, added up chunk by chunk (ChainLanes on several threads): the sums
// are those of one film that took every add, whichever films took them and in whatever
// chunks and order they are merged; a lane's film is empty after the merge and merging it again
// adds nothing. 97 x 61 pixels: the last chunk is partial.
TEST(ExactFilm, LaneFilmsMergedByChunksEqualOneFilm) {
  const int w = 97, h = 61;
  const double unit = std::ldexp(1.0, -24);
  ExactFilm one(w, h, unit, false), merged(w, h, unit, false);
  std::vector<ExactFilm> lanes;
  for (int l = 0; l < 3; ++l) {
    lanes.emplace_back(w, h, unit, false);
    lanes.back().trackTouchedChunks();
  }
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> value(0, 1);
  // Lane 2 only ever adds to the first rows: its other chunks are never read.
  for (int i = 0; i < 30000; ++i) {
    const int lane = int(rng() % 3);
    const uint32_t pixel = uint32_t(rng() % (lane == 2 ? 200u : uint32_t(w * h)));
    const Color c(value(rng), value(rng), value(rng));
    const float weight = value(rng);
    one.add(pixel, c, weight);
    lanes[size_t(lane)].add(pixel, c, weight);
    if (i == 15000)  // a merge half-way, as after a batch's run of the lanes
      for (auto& lane : lanes) merged.takeChunks(lane, 0, merged.chunks());
  }
  ASSERT_GT(merged.chunks(), 5u);
  for (size_t first = 0; first < merged.chunks(); first += 2)  // in ranges, lanes in reverse
    for (size_t l = lanes.size(); l-- > 0;) merged.takeChunks(lanes[l], first, std::min(first + 2, merged.chunks()));
  RgbImage a{w, h, std::vector<Color>(size_t(w * h)), {}}, b = a, empty = a, lane = a;
  one.addTo(a, 1.0);
  merged.addTo(b, 1.0);
  test::expectBitIdentical(a, b);
  for (auto& l : lanes) {
    l.addTo(lane, 1.0);
    merged.takeChunks(l, 0, merged.chunks());
  }
  test::expectBitIdentical(lane, empty);
  RgbImage again = empty;
  merged.addTo(again, 1.0);
  test::expectBitIdentical(again, a);
}

TEST(ExactFilm, RefusesValuesBeyondItsRangeAndNaN) {
  const double unit = 1e-6;
  ExactFilm film(1, 1, unit, false);
  EXPECT_TRUE(film.fits(Color(float(0.5 * ExactFilm::kMaxCounts * unit))));
  EXPECT_FALSE(film.fits(Color(0, float(2 * ExactFilm::kMaxCounts * unit), 0)));
  EXPECT_FALSE(film.fits(Color(std::nanf(""), 0, 0)));
}

// The split-render reduce sends each count as two doubles: exact for negative counts and
// counts above 2^53 too.
TEST(ExactFilm, ReduceAcrossProcessesIsExact) {
  ExactFilm a(1, 1, 1.0, false), b(1, 1, 1.0, false);
  a.add(0, Color(3e15f, -7.0f, 123456789.0f), 1.0f);
  b.add(0, Color(5e15f, 2.0f, 1.0f), 1.0f);
  ByteWriter wb;
  b.save(wb);
  // The "other process": adds b's halves to a's, as MPI_Allreduce would.
  ExactFilm other(1, 1, 1.0, false);
  ByteReader rb(wb.bytes());
  other.load(rb);
  std::vector<double> fromOther;
  other.reduce([&](std::vector<double>& v) { fromOther = v; });
  a.reduce([&](std::vector<double>& v) {
    for (size_t i = 0; i < v.size(); ++i) v[i] += fromOther[i];
  });
  RgbImage img{1, 1, {Color(0)}, {}};
  a.addTo(img, 1.0);
  EXPECT_EQ(img.pixels[0].x, float(double(3e15f) + double(5e15f)));
  EXPECT_EQ(img.pixels[0].y, -5.0f);
  EXPECT_EQ(img.pixels[0].z, 123456790.0f);
}

struct LaneRun {
  RgbImage image;
  ChainStats stats;
};

// The world's seeds through a chain machine of `lanes` lanes of 64 slots (chains wait for
// slots and the lanes take them as they free up) on a pool of 2 threads.
LaneRun runLanes(const ErptWorld& w, const StepConfig& ctx, const ChainSettings& settings, int lanes,
                 double depositEnergy) {
  ThreadPool pool(2);
  Film film(w.width, w.height);
  LaneRun run;
  StageTimes times;
  ChainLanes::Config config{ctx, settings, 11, 64, depositEnergy};
  config.lanes = lanes;
  ChainLanes chains(*w.tracer, config, film, run.stats, times);
  SeedStore seeds = w.seeds;  // consume folds long seeds in place
  EXPECT_TRUE(chains.consume(seeds));
  EXPECT_TRUE(chains.finish());
  run.image = chains.image(1.0);
  return run;
}

void expectSameRuns(const LaneRun& a, const LaneRun& b) {
  test::expectBitIdentical(a.image, b.image);
  EXPECT_EQ(a.stats.chains, b.stats.chains);
  EXPECT_EQ(a.stats.mutations, b.stats.mutations);
  for (int k = 0; k < kMutationKindCount; ++k) EXPECT_EQ(a.stats.accepted[k], b.stats.accepted[k]) << k;
}

// 1, 2 and 5 lanes: the same chains (numbered by seed, not by lane or slot), the same image
// bits. Tent filter (deposits over up to 4 pixels), expected-value deposits (two records of
// very different sizes per step) and both noise filters (per-slot run state, the shared tally).
TEST(ErptLanes, SameImageForAnyLaneCount) {
  ErptWorld w(defaultScene(), 32, 2, FilterKind::Tent);
  StepConfig ctx = w.stepContext(MutationStrategy::Mixed);
  ChainSettings chains;
  chains.chainLength = 9;
  chains.directSamples = -1;
  chains.maxConsecutive = 4;
  chains.pmFilterRadius = 2;
  const LaneRun one = runLanes(w, ctx, chains, 1, 0.01);
  ASSERT_GT(one.stats.chains, 5u * 64u);  // every lane refills many times
  expectSameRuns(one, runLanes(w, ctx, chains, 2, 0.01));
  expectSameRuns(one, runLanes(w, ctx, chains, 5, 0.01));
}

// A tiny e_d caps every seed's chain count, so each step deposits far more than 2^16 e_d: all
// deposits take the large-deposit way (a double film, in chain order) and the image is still
// the same for any lane count.
TEST(ErptLanes, LargeDepositsGiveTheSameImageForAnyLaneCount) {
  ErptWorld w(defaultScene(), 24, 2, FilterKind::Tent);
  StepConfig ctx = w.stepContext(MutationStrategy::Mixed);
  ChainSettings chains;
  chains.chainLength = 6;
  chains.directSamples = -1;
  chains.maxChainsPerSeed = 2;
  const LaneRun one = runLanes(w, ctx, chains, 1, 1e-12);
  ASSERT_GT(one.stats.cappedSeeds, 100u);
  expectSameRuns(one, runLanes(w, ctx, chains, 3, 1e-12));
}

// Large deposits reach the double film in the order of (chain key, step, record), whatever
// order the lanes handed them over in: values over 15 decades on one pixel, whose double sum
// depends on the order, give the same bits from two orders.
TEST(ErptLanes, LargeDepositsAreAddedInChainOrder) {
  ErptWorld w(defaultScene(), 4, 1, FilterKind::Box);
  std::mt19937 rng(9);
  std::vector<LargeDeposit> records;
  for (uint32_t i = 0; i < 2000; ++i) {  // one record per (key, step, record), as chains make them
    const float v = std::pow(10.0f, float(int(rng() % 16)) - 12);
    records.push_back(LargeDeposit{i / 40, (i / 2) % 20, i % 2, 1.5f, 2.5f, Color(v, v, v)});
  }
  std::vector<LargeDeposit> shuffled = records;
  std::shuffle(shuffled.begin(), shuffled.end(), rng);
  Film a(4, 4), b(4, 4), unsorted(4, 4);
  for (const LargeDeposit& d : shuffled) unsorted.add(1 + 2 * 4, d.energy);
  addLargeDeposits(records, *w.density, a);
  addLargeDeposits(shuffled, *w.density, b);
  EXPECT_TRUE(records.empty());
  // The films' double sums, compared bit for bit.
  const auto sums = [](const Film& f) {
    ByteWriter w;
    f.save(w);
    return w.take();
  };
  EXPECT_EQ(sums(a), sums(b));
  // The shuffled order summed as it came differs (what the sort is for).
  EXPECT_NE(sums(unsorted), sums(a));
}

// A stop (Config::stop) leaves no energy behind: every chain still running deposits its
// remaining steps' energy where it stands and every chain still waiting for a slot deposits all
// of its energy at its seed, so the film holds what the uninterrupted run deposits, to the
// rounding of the sums (a stop in consume, with chains waiting, and one in finish).
TEST(ErptLanes, AStopDepositsTheEnergyOfEveryChainLeft) {
  ErptWorld w(defaultScene(), 32, 2, FilterKind::Box);
  const StepConfig ctx = w.stepContext(MutationStrategy::Mixed);
  ChainSettings settings;
  settings.chainLength = 40;
  settings.directSamples = -1;
  const double ed = 0.002;
  auto energyOf = [](const RgbImage& image) {
    double sum = 0;
    for (const Color& c : image.pixels) sum += double(luminance(c));
    return sum;
  };
  const LaneRun whole = runLanes(w, ctx, settings, 2, ed);
  ASSERT_GT(whole.stats.mutations, 20000u);
  for (const uint64_t stopAfter : {uint64_t(3000), whole.stats.mutations * 3 / 4}) {
    ThreadPool pool(2);
    Film film(w.width, w.height);
    ChainStats stats;
    StageTimes times;
    std::atomic<bool> stop{false};
    ChainLanes::Config config{ctx, settings, 11, 64, ed, &stop};
    config.lanes = 2;
    config.onSteps = [&](uint64_t steps) {
      if (steps >= stopAfter) stop = true;
    };
    ChainLanes chains(*w.tracer, config, film, stats, times);
    SeedStore seeds = w.seeds;
    const bool consumed = chains.consume(seeds);
    const bool finished = consumed && chains.finish();
    EXPECT_FALSE(finished) << stopAfter;
    EXPECT_LT(chains.stepsTaken(), whole.stats.mutations) << stopAfter;
    EXPECT_NEAR(energyOf(chains.image(1.0)), energyOf(whole.image), 1e-5 * energyOf(whole.image)) << stopAfter;
  }
  // Without the deposits of the chains left, the first stop would lose most of the energy.
}

// The chain maps' tallies (DepositFilters): each proposal a chain makes is counted once (also
// while slots wait empty at the end of a run), and its acceptance probability with it.
TEST(ErptLanes, ProposalTalliesCountEachProposalOnce) {
  ErptWorld w(defaultScene(), 32, 2, FilterKind::Box);
  ChainSettings settings;
  settings.chainLength = 30;
  settings.directSamples = -1;
  settings.chainMaps = true;
  ThreadPool pool(2);
  Film film(w.width, w.height);
  ChainStats stats;
  StageTimes times;
  ChainLanes::Config config{w.stepContext(MutationStrategy::LensOnly), settings, 11, 64, 0.002};
  config.lanes = 2;
  ChainLanes chains(*w.tracer, config, film, stats, times);
  SeedStore seeds = w.seeds;
  ASSERT_TRUE(chains.consume(seeds));
  ASSERT_TRUE(chains.finish());
  uint64_t counted = 0, acceptance = 0;
  for (uint32_t t : chains.tallies().proposals) counted += t;
  for (uint64_t a : chains.tallies().acceptance) acceptance += a;
  // Lens proposals count at their film position unless it is off the film.
  const uint64_t offFilm = stats.rejected[kRejectOffFilm];
  EXPECT_EQ(counted + offFilm, stats.mutations);
  const double meanQ = double(acceptance) * kAcceptanceUnit / double(counted);
  EXPECT_GT(meanQ, 0.05);
  EXPECT_LT(meanQ, 1.0);
}

}  // namespace
}  // namespace erpt
