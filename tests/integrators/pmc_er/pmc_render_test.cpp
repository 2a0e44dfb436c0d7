// PMC-ER in whole renders: unbiased against references and against the path tracer block by
// block, for both flows and the adaptation modes; deterministic for any thread count.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "erpt/erpt_settings.h"
#include "erpt/pmc_settings.h"
#include "erpt/image_io.h"
#include "erpt/render.h"
#include "erpt/scene_loader.h"
#include "support/block_bias.h"
#include "support/cornell_references.h"
#include "support/image_stats.h"
#include "support/in_place_reasons.h"
#include "support/test_support.h"

namespace erpt {
namespace {

RenderSettings pmcSettings(int spp, PmcFlow flow, PmcAdapt adapt, int population) {
  RenderSettings s;
  s.integrator = "pmc-er";
  s.spp = spp;
  pmcOf(s).flow = flow;
  pmcOf(s).adapt = adapt;
  pmcOf(s).population = population;
  chainOf(s).directSamples = -1;  // the paper's configuration: every path by PMC-ER
  return s;
}

using test::renderImage;

Scene defaultScene() { return loadScene(test::sourceDir() + "/scenes/default/scene.xml"); }
Scene plasticBox() { return loadScene(test::sourceDir() + "/tests/data/plastic-box.xml"); }

// Block by block (support/block_bias.h): PMC-ER renders of `spp` pool samples per pixel (a
// population of 1000, so that the 64x64 pool makes some 80 iterations per 8 spp) against
// 16 path-traced ones of 128 spp. The pool's samples are the path tracer's for the same
// seed, so rare bright paths (through the plastic coat onto the shadowed box faces) are as
// rare in a PMC-ER render as in a path-traced one of its spp; a dozen renders of 8 spp can
// all miss them in one block (measured: z -5.0 in one block for seeds 5300-5311 with either
// flow, -1.0 once 24 more renders are added). Hence 16 renders of 16 spp on the plastic box,
// and 24 for the balance flow, which keeps energy closer to where the pool found it (with 16,
// a change of the camera samples' strata alone moved its mean z^2 from under 2 to 2.07).
void blockByBlock(const Scene& scene, PmcFlow flow, PmcAdapt adapt, uint64_t seed, int spp, int runs) {
  test::expectMatchesPathTracerBlockByBlock(scene, pmcSettings(spp, flow, adapt, 1000), runs, seed);
}

// The default scene: caustics through the glass sphere, specular chains through both spheres.
// (Equal deposition on it: StatisticalPmc.StoppedRenderOfSeveralGroups in
// tests/integrators/resume_test.cpp, a render of several groups of passes stopped part-way.)
TEST(StatisticalPmc, DefaultSceneBalanceMatchesPathTracerBlockByBlock) {
  blockByBlock(defaultScene(), PmcFlow::Balance, PmcAdapt::Region, 5100, 8, 16);
}
// Plastic walls: a Dirac coat over a diffuse base at the same vertex.
TEST(StatisticalPmc, PlasticBoxEqualDepositionMatchesPathTracerBlockByBlock) {
  blockByBlock(plasticBox(), PmcFlow::EqualDeposition, PmcAdapt::Region, 5200, 16, 16);
}
TEST(StatisticalPmc, PlasticBoxBalanceMatchesPathTracerBlockByBlock) {
  blockByBlock(plasticBox(), PmcFlow::Balance, PmcAdapt::Region, 5300, 16, 24);
}
// The paper's per-member adaptation: a state-dependent kernel, not f-invariant in general
// (docs/pmc-er.md); no bias was detected at this precision (see docs/pmc-er.md, "Measured"; on the
// default scene, measured once: mean z^2 1.28, worst |z| 2.95, left out of the suite for time).
TEST(StatisticalPmc, PlasticBoxMemberAdaptationBlockByBlock) {
  blockByBlock(plasticBox(), PmcFlow::EqualDeposition, PmcAdapt::Member, 5500, 16, 16);
}

// The Cornell box at 128x128 with its defaults (population 5000, 4 mutations per member,
// radii 2/5/10, region adaptation): channel means within 1% of Tungsten's render, and the
// relative MSE against the 128x128 reference falling about 4x for 4x the pool (no floor).
TEST(StatisticalPmc, CornellBoxMatchesReferences) {
  const Scene scene = test::cornellBox();
  RenderSettings low = pmcSettings(4, PmcFlow::EqualDeposition, PmcAdapt::Region, 5000);
  low.width = low.height = 128;
  low.filterSet = true;
  low.filter = FilterKind::Box;
  RenderSettings high = low;
  high.spp = 16;
  high.seed = 2;
  RenderStats stats;
  const RgbImage a = renderImage(scene, low), b = renderImage(scene, high, &stats);
  test::expectCornellBoxConverges(a, b, 2.8, 6.0);
  // Every pool position was used, and the pilot's e_d (eq. 4) is what a step deposited on
  // average (the energy bookkeeping adds up; both are estimates, within a few percent).
  EXPECT_EQ(pmcStatsOf(stats).poolUsed, pmcStatsOf(stats).poolSize);
  EXPECT_EQ(pmcStatsOf(stats).poolSize, 128u * 128u * 16u);
  EXPECT_NEAR(pmcStatsOf(stats).meanDeposit / pmcStatsOf(stats).depositEnergy, 1.0, 0.05);
}

// The same scene, seed and options give the same image at 1 and 2 threads, bit for bit, for
// both flows and every adaptation mode: 1300 members are three lanes (kPmcLaneSlots), which
// two threads run at once, depositing into one film.
TEST(Pmc, SameImageForAnyThreadCount) {
  const Scene scene = defaultScene();
  for (PmcFlow flow : {PmcFlow::EqualDeposition, PmcFlow::Balance})
    for (PmcAdapt adapt : {PmcAdapt::Region, PmcAdapt::Member}) {
      RenderSettings s = pmcSettings(2, flow, adapt, 1300);
      s.width = s.height = 32;
      chainOf(s).directSamples = 2;
      s.threads = 1;
      const RgbImage a = renderImage(scene, s);
      s.threads = 2;
      const RgbImage b = renderImage(scene, s);
      test::expectBitIdentical(a, b);
    }
}

// Seeds no member can hold are deposited in place and counted by reason: under a directional
// light (tests/data/directional.xml) many are, for that reason, and the reasons add up to the
// total the summary gives.
TEST(Pmc, SeedsInPlaceAreCountedByReason) {
  test::expectInPlaceReasonsAddUp(pmcSettings(4, PmcFlow::EqualDeposition, PmcAdapt::Region, 1000), [](const RenderStats& st) { return pmcStatsOf(st).inPlaceSeeds; }, 200u);
}

}  // namespace
}  // namespace erpt
