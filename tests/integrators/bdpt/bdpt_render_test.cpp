// BDPT against the path tracer: whole renders block by block (z-scores over independent
// renders, support/block_bias.h) on scenes with every light type we support, each strategy
// (s, t) alone (unweighted) against the path tracer's paths of the same length, light tracing
// alone, and determinism.
#include <gtest/gtest.h>

#include "erpt/bdpt_settings.h"
#include "erpt/render.h"
#include "erpt/scene_loader.h"
#include "support/block_bias.h"
#include "support/cornell_references.h"
#include "support/environment_scene.h"
#include "support/image_stats.h"
#include "support/test_support.h"

namespace erpt {
namespace {

RenderSettings bdptSettings(int spp) {
  RenderSettings s;
  s.integrator = "bdpt";
  s.spp = spp;
  return s;
}

Scene dataScene(const std::string& name) { return loadScene(test::sourceDir() + "/tests/data/" + name); }

// Every strategy with its MIS weight (the default) against 16 path-traced renders of 128 spp.
TEST(StatisticalBdpt, CornellBoxMatchesPathTracerBlockByBlock) {
  test::expectMatchesPathTracerBlockByBlock(test::cornellBox(), bdptSettings(8), 16, 40000);
}

// Glass and mirror spheres: Dirac vertices, which no connection may join and whose densities
// the weights must carry through.
TEST(StatisticalBdpt, DefaultSceneMatchesPathTracerBlockByBlock) {
  test::expectMatchesPathTracerBlockByBlock(loadScene(test::sourceDir() + "/scenes/default/scene.xml"),
                                            bdptSettings(8), 16, 40100);
}

// Plastic: a smooth lobe and a Dirac coat at one vertex (connections evaluate the smooth part).
TEST(StatisticalBdpt, PlasticBoxMatchesPathTracerBlockByBlock) {
  test::expectMatchesPathTracerBlockByBlock(dataScene("plastic-box.xml"), bdptSettings(8), 16, 40200);
}

// Exact spherical lights, which next-event estimation samples in their cone and emission
// sampling by area: the one light whose next-event density differs from its emission density.
TEST(StatisticalBdpt, SphereLightsMatchPathTracerBlockByBlock) {
  test::expectMatchesPathTracerBlockByBlock(dataScene("sphere-lights.xml"), bdptSettings(8), 16, 40300);
}

// A small light focused by a glass sphere: most of the floor's light is caustic (found by
// light tracing and s >= 2 connections).
TEST(StatisticalBdpt, CausticSceneMatchesPathTracerBlockByBlock) {
  test::expectMatchesPathTracerBlockByBlock(dataScene("caustic-scene.xml"), bdptSettings(16), 16, 40400);
}

// Lights no camera path can hit: a spot (a Dirac in position, with its cone and falloff), a
// point light and a directional light (a Dirac in direction, emitted from a disk across the
// scene). Without specular surfaces: a path tracer cannot find a point or directional light's
// caustics (light -> glass -> floor -> camera), which BDPT's light tracing does, so over glass
// the path tracer is no reference (tests/data/spot-caustic.xml: BDPT is brighter there).
TEST(StatisticalBdpt, DeltaLightsMatchPathTracerBlockByBlock) {
  test::expectMatchesPathTracerBlockByBlock(dataScene("delta-lights.xml"), bdptSettings(8), 16, 40500);
}

// An environment map (importance-sampled directions, emitted from a disk) through glass.
TEST(StatisticalBdpt, EnvironmentMapMatchesPathTracerBlockByBlock) {
  test::TempDir dir;
  test::expectMatchesPathTracerBlockByBlock(loadScene(test::writeEnvmapGlassScene(dir)), bdptSettings(8), 16, 40700);
}

// Sun and sky (a directional sun and a sky map) through glass.
TEST(StatisticalBdpt, SunskyMatchesPathTracerBlockByBlock) {
  test::TempDir dir;
  test::expectMatchesPathTracerBlockByBlock(loadScene(test::writeSunskyGlassScene(dir)), bdptSettings(8), 16, 40800);
}

// Light tracing alone (t = 1, unweighted) renders a diffuse scene by itself: the lens
// connection, the camera's importance and the splat.
TEST(StatisticalBdpt, LightTracingAloneMatchesPathTracerBlockByBlock) {
  RenderSettings s = bdptSettings(16);
  bdptOf(s).onlyT = 1;
  bdptOf(s).unweighted = true;
  test::expectMatchesPathTracerBlockByBlock(test::cornellBox(), s, 16, 40900);
}

// Each strategy (s, t) alone and unweighted estimates every path of k = s + t - 1 segments it
// can make; on the diffuse Cornell box that is all of them, so each must match the path tracer
// restricted to paths of k segments (its render with max depth k minus one with k - 1, from
// independent seeds, block by block).
TEST(StatisticalBdpt, EachStrategyAloneMatchesPathTracerOfItsLength) {
  const Scene scene = test::cornellBox();
  const int runs = 12;
  auto base = [](RenderSettings s) {
    s.width = 48, s.height = 40;  // not powers of two
    s.filterSet = true;
    s.filter = FilterKind::Box;
    return s;
  };
  for (int k = 2; k <= 3; ++k) {
    std::vector<RgbImage> pathOfLengthK;
    for (int r = 0; r < runs; ++r) {
      RenderSettings s = base(RenderSettings{});
      s.integrator = "path";
      s.spp = 64;
      s.maxDepth = k;
      s.seed = 41000 + uint64_t(r);
      RgbImage upToK = test::renderImage(scene, s);
      s.maxDepth = k - 1;
      s.seed = 42000 + uint64_t(r);
      const RgbImage belowK = test::renderImage(scene, s);
      for (size_t p = 0; p < upToK.pixels.size(); ++p) upToK.pixels[p] = upToK.pixels[p] - belowK.pixels[p];
      pathOfLengthK.push_back(upToK);
    }
    for (int t = 1; t <= k + 1; ++t) {
      const int strategyS = k + 1 - t;
      std::vector<RgbImage> strategy;
      for (int r = 0; r < runs; ++r) {
        RenderSettings s = base(bdptSettings(t == 1 ? 32 : 16));
        bdptOf(s).onlyS = strategyS;
        bdptOf(s).onlyT = t;
        bdptOf(s).unweighted = true;
        s.seed = 43000 + uint64_t(r);
        strategy.push_back(test::renderImage(scene, s));
      }
      const test::BlockZScores z = test::blockZScores(strategy, pathOfLengthK, 8);
      std::printf("k = %d, (s, t) = (%d, %d): mean z^2 %.2f, worst |z| %.2f over %zu blocks\n", k, strategyS, t,
                  z.meanSquare, z.worst, z.z.size());
      EXPECT_GE(z.z.size(), 28u);  // of 30 (one at the top may be black)
      EXPECT_LT(z.meanSquare, 2.0) << "(s, t) = (" << strategyS << ", " << t << ")";
      EXPECT_LT(z.worst, 4.5) << "(s, t) = (" << strategyS << ", " << t << ")";
    }
  }
}

TEST(Bdpt, SameImageForAnyThreadCountAndSeed) {
  RenderSettings s = bdptSettings(4);
  s.width = 67, s.height = 45;
  s.threads = 1;
  const Scene scene = loadScene(test::sourceDir() + "/scenes/default/scene.xml");
  const RgbImage one = test::renderImage(scene, s);
  s.threads = 2;
  test::expectBitIdentical(one, test::renderImage(scene, s));
  s.seed = 99;
  EXPECT_GT(test::relativeMse(test::renderImage(scene, s), one), 0.0);
}

}  // namespace
}  // namespace erpt
