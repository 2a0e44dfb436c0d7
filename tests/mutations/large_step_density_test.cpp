// MLT's large step (large_step.h): the density it assigns to a path must be the density with
// which the path tracer made it. Every seed the path tracer records carries its unweighted
// estimate f / p_s for the technique s that made it (BSDF sample hitting the light, or
// next-event connection); the large step's terms, evaluated from the seed's vertices alone,
// must give the same number: value / pHit for hits, value / pNee for connections. This checks
// the BSDF densities and lobe choices, the Russian roulette factors and the light sampler's
// densities (triangles, spheres sampled by cone, point and spot lights, environment maps)
// that the large step's acceptance divides by.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "mutations/large_step.h"
#include "support/environment_scene.h"
#include "support/erpt_world.h"
#include "support/test_support.h"

namespace erpt {
namespace {

using test::ErptWorld;

struct Agreement {
  std::vector<double> errors, rouletteErrors;  // relative error of lum(estimate), all seeds / those past rrDepth
  size_t refused = 0, compared = 0;
};

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, size_t(q * double(v.size())))];
}

Agreement compareWithSeeds(const ErptWorld& w, int rrDepth) {
  Agreement a;
  const MeasureContext c = w.measure();
  PathVertex path[kMaxChainVertices];
  for (size_t s = 0; s < w.seeds.size(); ++s) {
    const SeedQueue& q = w.seeds.seeds;
    if (q.vertexCount[s] > uint32_t(kMaxChainVertices)) continue;
    const Color estimate(q.estimateR[s], q.estimateG[s], q.estimateB[s]);
    const float expected = luminance(estimate);
    if (!(expected > 0) || !std::isfinite(expected)) continue;
    const int n = w.seedPath(s, path);
    const int32_t light = path[n - 1].emitter;
    if (light >= 0 && w.scene.emitters[size_t(light)].kind == EmitterKind::Directional) continue;
    ++a.compared;
    LargeStepTerms t;
    const float p = largeStepTerms(c, rrDepth, path, n, t) ? (q.explicitLight[s] ? t.pNee : t.pHit) : 0.0f;
    if (!(p > 0)) {
      ++a.refused;
      continue;
    }
    const double err = std::abs(double(luminance(t.value)) / p - expected) / expected;
    a.errors.push_back(err);
    // The last bounce the BSDF sampled (at depth n - 2 for a hit, n - 3 for a connection) was
    // past the roulette's start: the estimate holds survival factors.
    if (n - 2 - int(q.explicitLight[s]) >= rrDepth) a.rouletteErrors.push_back(err);
  }
  return a;
}

void expectAgreement(const ErptWorld& w, const char* name, bool expectRoulette) {
  const Agreement a = compareWithSeeds(w, 5);
  SCOPED_TRACE(name);
  ASSERT_GT(a.compared, 500u);
  // Stored vertices round the directions the path tracer used: glossy lobes and Fresnel
  // factors then differ in the 5th-6th digit (measured: medians ~1e-7, 90% below 1e-5); a missing factor (a lobe probability, a
  // roulette survival, a light pick) is off by 5% or far more.
  EXPECT_LT(double(a.refused), 0.002 * double(a.compared)) << "seeds the large step says it cannot make";
  EXPECT_LT(quantile(a.errors, 0.5), 1e-5);
  EXPECT_LT(quantile(a.errors, 0.9), 1e-4);
  EXPECT_LT(quantile(a.errors, 0.99), 1e-3);
  if (expectRoulette) {
    ASSERT_GT(a.rouletteErrors.size(), 50u);
    EXPECT_LT(quantile(a.rouletteErrors, 0.5), 1e-5);
  }
  std::printf("%s: %zu seeds, %zu refused, relative error median %.2g, 90%% %.2g, 99%% %.2g; past the roulette %zu, median %.2g\n",
              name, a.compared, a.refused, quantile(a.errors, 0.5), quantile(a.errors, 0.9), quantile(a.errors, 0.99),
              a.rouletteErrors.size(), quantile(a.rouletteErrors, 0.5));
}

TEST(LargeStepDensity, CornellBoxSeedsMatchTheirEstimates) {
  const ErptWorld w(test::sharedScenesDir() + "/cornell-box/scene.xml", 32, 4, FilterKind::Box);
  expectAgreement(w, "cornell box", true);
}

TEST(LargeStepDensity, GlassAndMirrorSpheresSeedsMatchTheirEstimates) {
  const ErptWorld w(test::sourceDir() + "/scenes/default/scene.xml", 32, 4, FilterKind::Tent);
  expectAgreement(w, "default scene", true);
}

TEST(LargeStepDensity, SphereLightsSampledByConeMatchTheirEstimates) {
  const ErptWorld w(test::sourceDir() + "/tests/data/sphere-lights.xml", 32, 4, FilterKind::Box);
  expectAgreement(w, "sphere lights", false);
}

TEST(LargeStepDensity, SpotLightAndRoughGlassMatchTheirEstimates) {
  const ErptWorld spot(test::sourceDir() + "/tests/data/spot-caustic.xml", 32, 4, FilterKind::Box);
  expectAgreement(spot, "spot caustic", false);
  const ErptWorld rough(test::sourceDir() + "/tests/data/rough-glass.xml", 32, 4, FilterKind::Box);
  expectAgreement(rough, "rough glass", false);
}

TEST(LargeStepDensity, EnvironmentMapSeedsMatchTheirEstimates) {
  const test::TempDir dir;
  const ErptWorld w(test::writeEnvmapGlassScene(dir), 32, 4, FilterKind::Box);
  expectAgreement(w, "environment map", false);
}

}  // namespace
}  // namespace erpt
