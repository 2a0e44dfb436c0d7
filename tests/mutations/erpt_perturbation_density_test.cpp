// Each perturbation samples the density it states, checked by chi-square on the mutate stage's
// own proposals (one chain path, many random streams): the lens square (uniform in
// [-R, R]^2), the lens disk (uniform in the disk: r^2 / R^2 and phi uniform), ERPT's caustic
// angle (log theta uniform on [1e-4, 0.1]: density 1/theta) and Veach's (theta / theta_max
// uniform on [0, 1], theta_max from PMC-ER eq. 6), all with uniform azimuth.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "core/rng.h"
#include "support/chi_square.h"
#include "support/erpt_world.h"
#include "support/test_support.h"

namespace erpt {
namespace {

using test::ChainQueues;
using test::ErptWorld;

constexpr size_t kSamples = 64 * 1024;

// Chi-square p-value of counts against a uniform expectation over the bins.
double uniformPValue(const std::vector<uint64_t>& counts) {
  uint64_t total = 0;
  for (uint64_t c : counts) total += c;
  const double expected = double(total) / double(counts.size());
  double x2 = 0;
  for (uint64_t c : counts) x2 += (double(c) - expected) * (double(c) - expected) / expected;
  return test::chiSquarePValue(x2, int(counts.size()) - 1);
}

size_t binOf(double unit, size_t bins) { return std::min(bins - 1, size_t(std::max(0.0, unit) * double(bins))); }

// Every slot holds the same chain path (seed `seed`), each with its own random stream.
void loadCopies(const ErptWorld& w, ChainQueues& q, size_t seed) {
  for (size_t i = 0; i < q.chains.size(); ++i) loadChainFromSeed(q.chains, q.chainVertices, i, w.seeds, seed, streamKey(99, i, 0), 10, 1.0f);
}

// The first seed satisfying `wanted` (its kinds and film position).
size_t findSeed(const ErptWorld& w, const std::function<bool(const uint8_t*, int, float, float)>& wanted) {
  uint8_t kinds[kMaxChainVertices];
  for (size_t i = 0; i < w.seeds.size(); ++i) {
    const int n = int(w.seeds.seeds.vertexCount[i]);
    if (n > kMaxChainVertices || !(luminance(w.seeds.contribution(i)) > 0)) continue;
    for (int j = 0; j < n; ++j) kinds[j] = w.seeds.vertices.kind[w.seeds.seeds.vertexBegin[i] + size_t(j)];
    if (wanted(kinds, n, w.seeds.seeds.filmX[i], w.seeds.seeds.filmY[i])) return i;
  }
  return w.seeds.size();
}

void checkLens(LensShape shape) {
  ErptWorld w(test::sharedScenesDir() + "/cornell-box/scene.xml", 48, 1, FilterKind::Box);
  StepConfig ctx = w.stepContext(MutationStrategy::LensOnly);
  ctx.settings.lensShape = shape;
  const float radius = ctx.settings.lensRadius;
  const size_t seed = findSeed(w, [](const uint8_t*, int, float x, float y) { return x > 16 && x < 32 && y > 16 && y < 32; });
  ASSERT_LT(seed, w.seeds.size());
  ChainQueues q(kSamples);
  loadCopies(w, q, seed);
  stageChainMutate(ctx, q.chains, q.chainVertices, q.proposals, q.rays, IndexRange{0, kSamples});
  std::vector<uint64_t> a(64, 0), b(64, 0);
  for (size_t i = 0; i < kSamples; ++i) {
    ASSERT_EQ(q.proposals.mutation[i], uint8_t(ctx.lensKind()));
    const double dx = q.proposals.filmX[i] - q.chains.filmX[i], dy = q.proposals.filmY[i] - q.chains.filmY[i];
    if (shape == LensShape::Square) {
      ++a[binOf((dx / radius + 1) / 2, 8) * 8 + binOf((dy / radius + 1) / 2, 8)];
    } else {
      const double r2 = (dx * dx + dy * dy) / (radius * radius);
      ASSERT_LE(r2, 1.0 + 1e-4);
      ++a[binOf(r2, 8) * 8 + binOf((std::atan2(dy, dx) + kPi) / (2 * kPi), 8)];
    }
  }
  const double p = uniformPValue(a);
  std::printf("%s: p = %.3f\n", shape == LensShape::Square ? "square" : "disk", p);
  EXPECT_GT(p, 1e-3);
}

// `radius` > 0: the image move theta_max is computed for (default: the settings').
void checkCaustic(CausticAngle angle, float radius = 0) {
  ErptWorld w(test::sharedScenesDir() + "/cornell-box/scene.xml", 48, 1, FilterKind::Box);
  StepConfig ctx = w.stepContext(MutationStrategy::CausticOnly);
  ctx.settings.causticAngle = angle;
  if (radius > 0) ctx.settings.lensRadius = radius;
  const size_t seed = findSeed(w, [](const uint8_t* k, int n, float, float) { return causticSource(k, n) > 0; });
  ASSERT_LT(seed, w.seeds.size());
  PathVertex y[kMaxChainVertices];
  const int n = w.seedPath(seed, y);
  uint8_t kinds[kMaxChainVertices];
  for (int j = 0; j < n; ++j) kinds[j] = y[j].kind;
  const int s = causticSource(kinds, n);
  const Vec3 d0 = directionBetween(y[s], y[s - 1]);
  const Frame frame(d0);
  double toSource = 0;
  for (int k = 2; k <= s; ++k) toSource += double(length(y[k].p - y[k - 1].p));
  // theta_max of eq. 6, written out here, at most pi (uniform theta in [0, pi] covers the sphere).
  const double thetaMax = std::min(double(kPi), std::atan(double(ctx.settings.lensRadius) / double(w.camera->pixelsPerPlaneUnit())) *
                                                    double(length(y[1].p - w.camera->position())) / toSource);
  ChainQueues q(kSamples);
  loadCopies(w, q, seed);
  stageChainMutate(ctx, q.chains, q.chainVertices, q.proposals, q.rays, IndexRange{0, kSamples});
  std::vector<uint64_t> thetas(32, 0), phis(16, 0);
  for (size_t i = 0; i < kSamples; ++i) {
    ASSERT_EQ(q.proposals.mutation[i], uint8_t(ctx.causticKind()));
    const Vec3 d = normalize(q.rays.dirAt(i));
    const Vec3 local = frame.toLocal(d);
    const double theta = std::atan2(std::sqrt(double(local.x) * local.x + double(local.y) * local.y), double(local.z));
    const double unit = angle == CausticAngle::Veach
                            ? theta / thetaMax
                            : std::log(theta / kPerturbThetaMin) / std::log(double(kPerturbThetaMax / kPerturbThetaMin));
    ASSERT_LE(unit, 1.0 + 1e-3) << "theta " << theta;
    ++thetas[binOf(unit, thetas.size())];
    ++phis[binOf((std::atan2(double(local.y), double(local.x)) + kPi) / (2 * kPi), phis.size())];
  }
  const double pTheta = uniformPValue(thetas), pPhi = uniformPValue(phis);
  std::printf("%s: theta_max %.4g, p(theta) = %.3f, p(phi) = %.3f\n", angle == CausticAngle::Veach ? "veach" : "erpt",
              thetaMax, pTheta, pPhi);
  EXPECT_GT(pTheta, 1e-3);
  EXPECT_GT(pPhi, 1e-3);
}

TEST(ErptPerturbationDensity, LensSquareIsUniform) { checkLens(LensShape::Square); }
TEST(ErptPerturbationDensity, LensDiskIsUniform) { checkLens(LensShape::Disk); }
TEST(ErptPerturbationDensity, CausticErptAngleHasDensityOneOverTheta) { checkCaustic(CausticAngle::Erpt); }
TEST(ErptPerturbationDensity, CausticVeachAngleIsUniformUpToThetaMax) { checkCaustic(CausticAngle::Veach); }
// A move of 400 pixels asks eq. 6 for a theta_max beyond pi on this path: the
// angle range must stop at pi, where the directions have covered the sphere, or theta wraps
// around and the stated density is wrong (PMC-ER's 50-pixel radius reached it on the 64x64
// plastic box: energy moved between regions, mean z^2 3.4 per 8x8 block, before the clamp).
TEST(ErptPerturbationDensity, CausticVeachAngleStopsAtPi) { checkCaustic(CausticAngle::Veach, 400); }

}  // namespace
}  // namespace erpt
