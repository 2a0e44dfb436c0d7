// Seeds whose energy ERPT cannot redistribute are deposited where they are, counted by reason,
// never lost: no deposition energy (e_d = 0), a path of zero f in the mutation's measure;
// chain counts are capped without changing the total.
#include <gtest/gtest.h>

#include <cmath>

#include "integrators/chain_lanes.h"
#include "integrators/erpt/erpt_integrator.h"
#include "erpt/render.h"
#include "core/rng.h"
#include "erpt/scene_loader.h"
#include "support/erpt_world.h"
#include "support/test_support.h"

namespace erpt {
namespace {

using test::ChainQueues;
using test::ErptWorld;

std::string cornell() { return test::sharedScenesDir() + "/cornell-box/scene.xml"; }

// e_ave = 0 (a pilot pass that found no seed energy: tiny images, one pilot sample, dark
// scenes) gives e_d = 0: no chain can run, so every seed must be deposited at its own film
// position. The image is then the path tracer's, pixel by pixel (same seeds, same samples).
TEST(ErptInPlace, NoDepositionEnergyDepositsEverySeedWhereItIs) {
  const Scene scene = loadScene(cornell());
  RenderSettings s;
  s.width = s.height = 8;
  s.spp = 8;
  s.seed = 4;
  s.filterSet = true;
  s.filter = FilterKind::Box;
  s.integrator = "path";
  RenderStats pathStats;
  const RgbImage path = render(scene, s, pathStats);
  s.integrator = "erpt";
  chainOf(s).directSamples = -1;
  RenderStats stats;
  // As if the pilot pass had measured e_ave = 0.
  const RgbImage erpt = renderErptWith(scene, resolveSettings(scene, s), stats, ErptEnergies{0, 0});
  EXPECT_EQ(chainStatsOf(stats).depositEnergy, 0.0);
  EXPECT_EQ(chainStatsOf(stats).chains, 0u);
  ASSERT_GT(chainStatsOf(stats).seeds, 100u);
  EXPECT_EQ(chainStatsOf(stats).inPlace[kInPlaceNoDepositEnergy] +
                chainStatsOf(stats).inPlace[kInPlaceZeroContribution] + chainStatsOf(stats).inPlace[kInPlaceNoMutation],
            chainStatsOf(stats).seeds);
  EXPECT_GT(chainStatsOf(stats).inPlace[kInPlaceNoDepositEnergy], chainStatsOf(stats).seeds * 9 / 10);
  double sumPath = 0, sumErpt = 0;
  for (size_t i = 0; i < path.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(erpt.pixels[i][c], path.pixels[i][c], 1e-4 * (1 + path.pixels[i][c])) << "pixel " << i;
      sumPath += path.pixels[i][c];
      sumErpt += erpt.pixels[i][c];
    }
  EXPECT_GT(sumPath, 0.1);
  EXPECT_NEAR(sumErpt / sumPath, 1.0, 1e-4);
}

// A tiny e_d would start e / (m e_d) chains per seed (billions); the cap starts at most
// maxChainsPerSeed, each step depositing e / (m cap), so the total is each seed's e exactly.
TEST(ErptInPlace, ChainCountsAreCappedWithTheSameTotalEnergy) {
  ErptWorld w(cornell(), 16, 1, FilterKind::Box);
  Film film(w.width, w.height);
  ChainStats stats;
  StageTimes times;
  StepConfig ctx = w.stepContext(MutationStrategy::Paper);
  ChainSettings lanes;
  lanes.chainLength = 5;
  lanes.directSamples = -1;
  lanes.maxChainsPerSeed = 3;
  ChainLanes::Config config{ctx, lanes, 3, 512, 1e-12};
  ChainLanes chains(*w.tracer, config, film, stats, times);
  chains.consume(w.seeds);
  chains.finish();
  double seedEnergy = 0;
  for (size_t i = 0; i < w.seeds.size(); ++i) {
    const float e = luminance(w.seeds.contribution(i));
    if (e > 0 && std::isfinite(e)) seedEnergy += e;
  }
  ASSERT_GT(stats.seeds, 50u);
  uint64_t inPlace = 0;
  for (uint64_t n : stats.inPlace) inPlace += n;
  EXPECT_EQ(stats.cappedSeeds + inPlace, stats.seeds);
  EXPECT_EQ(stats.chains, 3 * stats.cappedSeeds);
  EXPECT_EQ(stats.mutations, stats.chains * 5);
  EXPECT_NEAR(chains.depositedEnergy() / seedEnergy, 1.0, 1e-4);
}

// A seed whose path has zero f in its mutation's measure (here: its light vertex turned away,
// so the one-sided emitter sends nothing along the path; the stored estimate is unchanged)
// must not start chains (they would stand on a zero of their target and accept everything):
// its energy is deposited at its film position and counted.
TEST(ErptInPlace, SeedWithZeroContributionIsDepositedInPlace) {
  ErptWorld w(cornell(), 16, 1, FilterKind::Box);
  // The first seed of three or more vertices that reached an area light by next-event
  // estimation: flip its light's normal.
  size_t chosen = w.seeds.size();
  for (size_t i = 0; i < w.seeds.size() && chosen == w.seeds.size(); ++i)
    if (w.seeds.seeds.explicitLight[i] && w.seeds.seeds.vertexCount[i] == 3 && luminance(w.seeds.contribution(i)) > 0)
      chosen = i;
  ASSERT_LT(chosen, w.seeds.size());
  SeedStore one;
  one.seeds.resize(1);
  one.seeds.copyRow(0, w.seeds.seeds, chosen);
  one.vertices.resize(3);
  for (size_t j = 0; j < 3; ++j) one.vertices.copyRow(j, w.seeds.vertices, w.seeds.seeds.vertexBegin[chosen] + j);
  one.seeds.vertexBegin[0] = 0;
  one.vertices.ngX[2] = -one.vertices.ngX[2];
  one.vertices.ngY[2] = -one.vertices.ngY[2];
  one.vertices.ngZ[2] = -one.vertices.ngZ[2];
  Film film(w.width, w.height);
  ChainStats stats;
  StageTimes times;
  StepConfig ctx = w.stepContext(MutationStrategy::LensOnly);
  ChainSettings lanes;
  lanes.chainLength = 10;
  lanes.directSamples = -1;
  ChainLanes::Config config{ctx, lanes, 3, 64, double(luminance(one.contribution(0))) / 40};  // 4 chains if it could move
  ChainLanes chains(*w.tracer, config, film, stats, times);
  chains.consume(one);
  chains.finish();
  EXPECT_EQ(stats.inPlace[kInPlaceZeroContribution], 1u);
  EXPECT_EQ(stats.chains, 0u);
  EXPECT_EQ(stats.mutations, 0u);
  const RgbImage img = chains.image(1.0);
  const uint32_t pixel = one.seeds.pixel[0];
  EXPECT_NEAR(luminance(img.pixels[pixel]) / luminance(one.contribution(0)), 1.0, 1e-5);
}

// The accept stage's guard: a chain whose cached f(y) is zero in the chosen mutation's measure
// rejects every proposal (with q = 1 it would accept anything).
TEST(ErptInPlace, ChainOnAZeroOfItsTargetAcceptsNothing) {
  ErptWorld w(cornell(), 32, 2, FilterKind::Box);
  ChainQueues q(1024);
  const size_t loaded = q.loadSeeds(w, 10, 1.0f, 5);
  ASSERT_GT(loaded, 500u);
  const StepConfig ctx = w.stepContext(MutationStrategy::LensOnly);
  for (size_t i = 0; i < loaded; ++i) {
    q.chains.fLum[i] = 0;
    q.chains.fKind[i] = uint8_t(MutationKind::Lens);
  }
  q.propose(w, ctx);
  StepCounters counters;
  stageChainAccept(ctx, q.chains, q.chainVertices, q.proposals, q.proposalVertices, q.deposits, counters,
                  IndexRange{0, q.chains.size()});
  size_t complete = 0;
  for (size_t i = 0; i < loaded; ++i) {
    EXPECT_EQ(q.proposals.acceptance[i], 0.0f) << "slot " << i;
    if (q.proposals.state[i] == kProposalComplete && q.proposals.reason[i] != kRejectZero) {
      EXPECT_EQ(q.proposals.reason[i], kRejectCurrentZero);
      ++complete;
    }
  }
  EXPECT_GT(complete, loaded / 10);
  EXPECT_EQ(counters.accepted[size_t(MutationKind::Lens)], 0u);
}

// The pool (bench/scenes/pool) is lit through its water, and some of its seeds bounce between
// the floor and the water's underside: E S D S D S ... L, 13 to 19 vertices, which only the
// lens perturbation carried through to the light can move. Chains hold them whole, so none is
// deposited in place for its length, and every other one has a mutation (with chains of 12
// vertices about one seed in 500 stayed in place, folded).
TEST(ErptInPlace, LongSpecularChainsOfThePoolAreHeldWhole) {
  const Scene scene = loadScene(test::sourceDir() + "/bench/scenes/pool/scene.xml");
  RenderSettings s;
  s.width = 96;
  s.height = 72;
  s.spp = 16;
  s.seed = 3;
  s.integrator = "erpt";
  erptOf(s).chainLength = 2;
  RenderStats stats;
  render(scene, s, stats);
  const ChainStats& c = chainStatsOf(stats);
  ASSERT_GT(c.seeds, 5000u);
  EXPECT_EQ(c.inPlace[kInPlaceFoldedChain], 0u);
  EXPECT_EQ(c.inPlace[kInPlaceNoMutation], 0u);
}

}  // namespace
}  // namespace erpt
