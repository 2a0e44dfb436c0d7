// Whole ERPT renders: unbiasedness against references, convergence without a floor,
// stationarity of lens-only and caustic-only chains, determinism.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "erpt/erpt_settings.h"
#include "erpt/render.h"
#include "erpt/scene_loader.h"
#include "support/image_stats.h"
#include "support/cornell_references.h"
#include "support/test_support.h"

namespace erpt {
namespace {

using test::meanOf;

struct ErptRun {
  int spp = 16, mutations = 100, chainLength = 100, directSamples = -1, size = 0, threads = 0;
  uint64_t seed = 1;
  MutationStrategy strategy = MutationStrategy::Paper;
  LensShape lensShape = LensShape::Square;
  CausticAngle causticAngle = CausticAngle::Erpt;
  bool expected = false;
  FilterKind filter = FilterKind::Box;
  int maxConsecutive = 0, pmFilterRadius = -1;  // noise filters, off
  float manifold = 0;  // --manifold-perturbation
};

RgbImage renderErptImage(const Scene& scene, const ErptRun& r, RenderStats* statsOut = nullptr) {
  RenderSettings s;
  s.integrator = "erpt";
  s.spp = r.spp;
  s.seed = r.seed;
  s.threads = r.threads;
  if (r.size > 0) s.width = s.height = r.size;
  s.filterSet = true;
  s.filter = r.filter;
  chainOf(s).mutationsPerPixel = r.mutations;
  erptOf(s).chainLength = r.chainLength;
  chainOf(s).directSamples = r.directSamples;
  chainOf(s).strategy = r.strategy;
  chainOf(s).lensShape = r.lensShape;
  chainOf(s).causticAngle = r.causticAngle;
  chainOf(s).expectedDeposit = r.expected;
  chainOf(s).maxConsecutive = r.maxConsecutive;
  chainOf(s).pmFilterRadius = r.pmFilterRadius;
  chainOf(s).manifoldPerturbation = r.manifold;
  RenderStats stats;
  RgbImage img = render(scene, s, stats);
  EXPECT_EQ(stats.invalidSamples, 0u);
  if (statsOut) *statsOut = stats;
  return img;
}

void expectMeansWithin(const RgbImage& img, const RgbImage& ref, double tolerance) {
  const Color m = meanOf(img), r = meanOf(ref);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(m[c] / r[c], 1.0, tolerance) << "channel " << c;
  std::printf("means %.4f %.4f %.4f vs %.4f %.4f %.4f\n", m.x, m.y, m.z, r.x, r.y, r.z);
}

// The paper's ERPT (chains on every path, direct light included) on the Cornell box: channel
// means within 2% of Tungsten's render, and relative MSE against the 128x128 reference
// falling by about 4 when seeds and mutations grow 4x (no bias floor). The means of `high`
// over seeds 1-10 spread with a standard deviation of 0.5% (mean ratio 1.003; MLT's and
// PMC-ER's runs of their test spread 0.2%), so 2% is four of them; a 1% bound failed on a
// change that moved the seed pass by rounding only (seed 2: 1.0101).
TEST(StatisticalErpt, CornellBoxMatchesReferences) {
  const Scene scene = test::cornellBox();
  ErptRun low;
  low.spp = 8;
  low.mutations = 50;
  low.size = 128;
  ErptRun high = low;
  high.spp = 32;
  high.mutations = 200;
  high.seed = 2;
  const RgbImage a = renderErptImage(scene, low), b = renderErptImage(scene, high);
  test::expectCornellBoxConverges(a, b, 2.8, 6.0, 0.02);
}

// The default configuration (one-bounce paths by the direct pass) on the default scene, whose
// glass sphere makes caustics, against a long path-traced render (tests/data, made with
// `erpt render scenes/default/scene.xml --integrator path --width 64 --height 64 --spp 16384
// --seed 7`).
TEST(StatisticalErpt, DefaultSceneMatchesLongPathTracedRender) {
  const Scene scene = loadScene(test::sourceDir() + "/scenes/default/scene.xml");
  const RgbImage ref = readImage(test::sourceDir() + "/tests/data/default-scene-path-64.exr");
  ErptRun low;
  low.spp = 8;
  low.mutations = 50;
  low.size = 64;
  low.directSamples = 8;
  low.filter = FilterKind::Tent;
  ErptRun high = low;
  high.spp = 32;
  high.mutations = 200;
  high.directSamples = 32;
  high.seed = 2;
  const RgbImage a = renderErptImage(scene, low), b = renderErptImage(scene, high);
  // One such render's channel means scatter by about 1% (measured over 12 seeds: standard
  // deviation 0.98%, mean ratio 1.0002), as much as the tolerance: the means are checked on
  // the average of eight independent renders (0.35%), so the 1% bound has a margin of ~3
  // standard deviations.
  RgbImage average = b;
  for (int k = 1; k < 8; ++k) {
    ErptRun more = high;
    more.seed = 2 + uint64_t(k);
    const RgbImage c = renderErptImage(scene, more);
    for (size_t i = 0; i < average.pixels.size(); ++i) average.pixels[i] += c.pixels[i];
  }
  for (Color& p : average.pixels) p = p / 8.0f;
  expectMeansWithin(average, ref, 0.01);
  const double ea = test::relativeMse(a, ref), eb = test::relativeMse(b, ref);
  std::printf("relMSE %.3g -> %.3g, ratio %.2f\n", ea, eb, ea / eb);
  EXPECT_GT(ea / eb, 2.8);
  EXPECT_LT(ea / eb, 6.0);
}


// Typical relative error on a coarse grid: the 75th percentile over 4x4-pixel blocks of
// |block luminance / reference block luminance - 1|. A percentile, not a mean, because caustic
// paths give both images rare very bright samples; a wrong density moves energy between
// regions and shows in most blocks.
double blockError(const RgbImage& img, const RgbImage& ref) {
  std::vector<double> errors;
  for (int by = 0; by < img.height / 4; ++by)
    for (int bx = 0; bx < img.width / 4; ++bx) {
      double e = 0, f = 0;
      for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
          e += luminance(img.at(bx * 4 + x, by * 4 + y));
          f += luminance(ref.at(bx * 4 + x, by * 4 + y));
        }
      if (f > 0) errors.push_back(std::abs(e / f - 1));
    }
  std::sort(errors.begin(), errors.end());
  return errors[errors.size() * 3 / 4];
}

// Stationarity per mutation kind: chains that only use lens (or only caustic) perturbations,
// started from path-traced seeds and run long (m = 1000), must keep the path-traced
// distribution, so the image they deposit (deposits = visits x e_d) converges to a converged
// path-traced image on a coarse grid (4x4-pixel blocks): the block error falls when seeds and
// mutations grow 4x, with no floor. The scene (tests/data/caustic-scene.xml) is a glass sphere
// over a diffuse floor under a small light; paths a kind cannot mutate keep their chains in
// place.
void expectStationary(MutationStrategy strategy, double bound, LensShape shape = LensShape::Square,
                      CausticAngle angle = CausticAngle::Erpt) {
  const Scene scene = loadScene(test::sourceDir() + "/tests/data/caustic-scene.xml");
  const RgbImage ref = readImage(test::sourceDir() + "/tests/data/caustic-scene-path-32.exr");
  double errors[2];
  for (int level = 0; level < 2; ++level) {
    ErptRun r;
    r.spp = 64 << (2 * level);
    r.mutations = 16 * r.spp;
    r.chainLength = 1000;
    r.strategy = strategy;
    r.lensShape = shape;
    r.causticAngle = angle;
    r.seed = 3 + level;
    RenderStats stats;
    const RgbImage img = renderErptImage(scene, r, &stats);
    uint64_t moved = 0;
    for (uint64_t a : chainStatsOf(stats).accepted) moved += a;
    EXPECT_GT(moved, chainStatsOf(stats).mutations / 3);
    errors[level] = blockError(img, ref);
    std::printf("%d spp, %d mutations/pixel: %.1f%% accepted, block error %.5f\n", r.spp, r.mutations,
                100.0 * double(moved) / double(chainStatsOf(stats).mutations), errors[level]);
  }
  std::printf("ratio %.2f\n", errors[0] / errors[1]);
  // Noise alone halves the typical error for 4x the samples (measured: 2.3x lens, 2.2x
  // caustic); a wrong density leaves a floor (measured with the lens connection's geometry
  // term dropped: 0.195 -> 0.198; caustic with cos^3 -> cos: 0.150 -> 0.087).
  EXPECT_GT(errors[0] / errors[1], 1.6);
  EXPECT_LT(errors[1], bound);
}

// Measured bounds: lens 0.027 (the same chains with a broken geometry term: 0.198).
TEST(StatisticalErpt, LensOnlyChainsKeepThePathTracedDistribution) { expectStationary(MutationStrategy::LensOnly, 0.05); }
// Caustic perturbations move chains little, so their images are noisier: measured 0.057 (with
// a broken rule 5: 0.087). ErptMeasure checks the caustic densities far more sharply.
TEST(StatisticalErpt, CausticOnlyChainsKeepThePathTracedDistribution) {
  expectStationary(MutationStrategy::CausticOnly, 0.075);
}

// The PMC-ER perturbations (disk lens, Veach's caustic angle with its asymmetric T) keep the
// distribution too, with the bounds of their ERPT counterparts.
TEST(StatisticalErpt, LensDiskChainsKeepThePathTracedDistribution) {
  expectStationary(MutationStrategy::LensOnly, 0.05, LensShape::Disk);
}
TEST(StatisticalErpt, CausticVeachChainsKeepThePathTracedDistribution) {
  expectStationary(MutationStrategy::CausticOnly, 0.075, LensShape::Square, CausticAngle::Veach);
}

// A small ERPT render of the default scene (caustics, specular chains).
ErptRun smallDefaultSceneRun() {
  ErptRun r;
  r.spp = 4;
  r.mutations = 20;
  r.chainLength = 20;
  r.size = 40;
  r.directSamples = 4;
  return r;
}

void expectSameImageAtOneAndTwoThreads(ErptRun r) {
  const Scene scene = loadScene(test::sourceDir() + "/scenes/default/scene.xml");
  r.threads = 1;
  const RgbImage a = renderErptImage(scene, r);
  r.threads = 2;
  const RgbImage b = renderErptImage(scene, r);
  test::expectBitIdentical(a, b);
}

// The same scene, seed and options give the same image at 1 and 2 threads, bit for bit.
TEST(Erpt, SameImageForAnyThreadCount) {
  ErptRun r = smallDefaultSceneRun();
  r.strategy = MutationStrategy::Mixed;
  expectSameImageAtOneAndTwoThreads(r);
}

// The same with a filter wider than a pixel (deposits reach up to four pixels), expected-value
// deposits and both noise filters (per-chain run state, the proposal tally); proposals walking
// specular chains go through the dense batches of later bounces in both.
// The manifold perturbation's walks run per range of its proposals, each with its own ray
// streams and scratch: their results must not depend on how the ranges fall on threads.
TEST(Erpt, SameImageForAnyThreadCountWithManifoldPerturbation) {
  ErptRun r = smallDefaultSceneRun();
  r.manifold = 0.5f;
  expectSameImageAtOneAndTwoThreads(r);
}

TEST(Erpt, SameImageForAnyThreadCountWithTentFilterAndNoiseFilters) {
  ErptRun r = smallDefaultSceneRun();
  r.filter = FilterKind::Tent;
  r.expected = true;
  r.maxConsecutive = 5;
  r.pmFilterRadius = 3;
  expectSameImageAtOneAndTwoThreads(r);
}

}  // namespace
}  // namespace erpt
