// Folded paths (foldSeedTail): a seed longer than a chain holds keeps its first
// kMaxChainVertices - 1 vertices and a tail vertex carrying the factor of the rest. Every
// quantity a chain computes from the folded path must equal the one from the whole path: the
// fixed tail from any vertex, and f in the lens perturbation's measure. A wrong tail factor
// (its area factor left out, or taken from the wrong vertex) moves these by far more than
// float rounding.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "integrators/seed_checks.h"
#include "mutations/mutation.h"
#include "mutations/path_factors.h"
#include "support/erpt_world.h"
#include "support/test_support.h"

namespace erpt {
namespace {

using test::ErptWorld;

double relativeDifference(Color a, Color b) {
  const double la = luminance(a), lb = luminance(b);
  return std::abs(la - lb) / std::max(1e-30, std::max(std::abs(la), std::abs(lb)));
}

TEST(FoldedTail, FoldedSeedsKeepEveryFactorAndTheirLensContribution) {
  // Folded at 12 vertices rather than the chains' 21: the fold's arithmetic does not depend on
  // where it is made, and the Cornell box's seeds have hundreds of paths longer than 12.
  constexpr int kKeep = 12;
  ErptWorld w(test::sharedScenesDir() + "/cornell-box/scene.xml", 32, 32, FilterKind::Box, 5);
  const StepConfig ctx = w.stepContext(MutationStrategy::Paper);
  SeedStore folded = w.seeds;
  size_t longSeeds = 0, lensChecked = 0;
  std::vector<double> tailErrors, lensErrors;
  for (size_t i = 0; i < w.seeds.size(); ++i) {
    const int n = int(w.seeds.seeds.vertexCount[i]);
    if (n <= kKeep || !(luminance(w.seeds.contribution(i)) > 0)) continue;
    ++longSeeds;
    std::vector<PathVertex> whole(size_t(n) + 0);
    for (int j = 0; j < n; ++j) loadPathVertex(w.seeds.vertices, w.seeds.seeds.vertexBegin[i] + size_t(j), whole[size_t(j)]);
    foldSeedTail(ctx, folded, i, kKeep);
    ASSERT_EQ(folded.seeds.vertexCount[i], uint32_t(kKeep));
    PathVertex path[kKeep];
    for (int j = 0; j < kKeep; ++j) loadPathVertex(folded.vertices, folded.seeds.vertexBegin[i] + size_t(j), path[j]);
    ASSERT_EQ(path[kKeep - 1].kind, kTailVertex);
    for (int j = 0; j + 1 < kKeep; ++j) ASSERT_EQ(path[j].kind, whole[size_t(j)].kind);
    for (int first = 2; first < kKeep; ++first) {
      const Color full = factors::fixedTail(ctx.measure, whole.data(), n, first);
      if (!(luminance(full) > 0)) continue;
      tailErrors.push_back(relativeDifference(full, factors::fixedTail(ctx.measure, path, kKeep, first)));
    }
    const float x = w.seeds.seeds.filmX[i], y = w.seeds.seeds.filmY[i];
    const Color lensWhole = lensContribution(ctx.measure, whole.data(), n, x, y);
    if (luminance(lensWhole) > 0) {
      ++lensChecked;
      lensErrors.push_back(relativeDifference(lensWhole, lensContribution(ctx.measure, path, kKeep, x, y)));
    }
  }
  // The Cornell box at 32 x 32, 32 spp, unbounded depth: about 500 paths of 13 or more vertices.
  ASSERT_GT(longSeeds, 50u);
  ASSERT_GT(lensChecked, 50u);
  std::sort(tailErrors.begin(), tailErrors.end());
  std::sort(lensErrors.begin(), lensErrors.end());
  // Float products in a different order: a few ulps per factor; the median far below 1e-5.
  EXPECT_LT(tailErrors[tailErrors.size() / 2], 1e-5);
  EXPECT_LT(tailErrors[tailErrors.size() * 99 / 100], 1e-4);
  EXPECT_LT(lensErrors[lensErrors.size() / 2], 1e-5);
  EXPECT_LT(lensErrors[lensErrors.size() * 99 / 100], 1e-4);
}

// A folded path stays movable where its prefix allows: the lens perturbation applies when its
// connection comes before the tail vertex, never when the walk would have to pass it.
TEST(FoldedTail, LensAppliesOnlyBeforeTheTailVertex) {
  const int n = kMaxChainVertices;
  uint8_t kinds[kMaxChainVertices];
  kinds[0] = kEyeVertex;
  for (int j = 1; j < n - 1; ++j) kinds[j] = kNonSpecularVertex;
  kinds[n - 1] = kTailVertex;
  EXPECT_NE(chooseMutation(MutationStrategy::Paper, kinds, n, 0.5f), MutationKind::None);
  for (int j = 2; j < n - 1; ++j) kinds[j] = kSpecularVertex;  // E D S ... S T: no connection
  EXPECT_EQ(chooseMutation(MutationStrategy::Paper, kinds, n, 0.5f), MutationKind::None);
  EXPECT_EQ(chooseMutation(MutationStrategy::Mixed, kinds, n, 0.1f), MutationKind::None);
  kinds[n - 2] = kNonSpecularVertex;  // E D S ... S D T: the connection would be the tail itself
  EXPECT_EQ(chooseMutation(MutationStrategy::Paper, kinds, n, 0.5f), MutationKind::None);
}

}  // namespace
}  // namespace erpt
