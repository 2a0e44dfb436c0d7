// Veach's bidirectional mutation (mutations/bidirectional.h):
//  - its plan sampler draws (l, m, added, eyeSide) with exactly the probabilities its
//    transition density uses (chi-square over every plan of several path lengths);
//  - detailed balance with explicit reverse moves on the Cornell box: for each complete
//    proposal z of a chain at y, the reverse move deletes z's new vertices and adds back as
//    many as y had there (l kept, m' = l + added + 1); the flow
//      f(y) T(y -> z) q(y -> z) = f(z) T(z -> y) q(z -> y)
//    must balance with T written out here from the stated densities of a diffuse scene with
//    area lights (film positions uniform, cosine-weighted BSDF and emission sampling, light
//    points uniform by area over each light, lights picked by power), not from the unit's
//    own density code;
//  - on the default scene (glass and mirror spheres) the reverse plan's ratio is the
//    reciprocal of the forward one for moves through specular vertices (the sum over splits
//    skips the ones that would connect at a Dirac vertex, both ways).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <tuple>
#include <vector>

#include "core/rng.h"
#include "mutations/bidirectional.h"
#include "stages/chain_step.h"
#include "support/chi_square.h"
#include "support/erpt_world.h"
#include "support/test_support.h"

namespace erpt {
namespace {

using test::ChainQueues;
using test::ErptWorld;

using PlanKey = std::tuple<int, int, int, int>;

// Every plan of an n-vertex path with its probability, from the three stated distributions.
std::map<PlanKey, double> planProbabilities(int n, bool deletable, VertexRange lengths) {
  std::map<PlanKey, double> p;
  const int mMax = deletable ? n : n - 1;
  for (int l = 0; l <= n - 2; ++l)
    for (int m = l + 1; m <= mMax; ++m)
      for (int added = 0; added <= kMaxChainVertices; ++added) {
        const double choice =
            deletionProbability(n, deletable, l, m) * additionProbability(n, lengths, l, m, added);
        if (!(choice > 0)) continue;
        const int tMin = eyeSideMin(l), tMax = eyeSideMax(n, m, added);
        for (int t = tMin; t <= tMax; ++t) p[{l, m, added, t}] = choice / (tMax - tMin + 1);
      }
  return p;
}

TEST(BidirectionalMutation, PlanSamplerDrawsThePlanProbabilities) {
  struct Case {
    int n;
    bool deletable;
    VertexRange lengths;
  };
  for (const Case& c : {Case{5, true, {2, 12}}, Case{4, false, {4, 8}}, Case{2, true, {2, 12}}, Case{11, true, {4, 12}},
                        Case{7, false, {2, 7}}}) {
    const std::map<PlanKey, double> p = planProbabilities(c.n, c.deletable, c.lengths);
    double total = 0;
    for (const auto& [key, prob] : p) total += prob;
    ASSERT_LE(total, 1 + 1e-9);
    constexpr uint64_t kDraws = 400000;
    std::map<PlanKey, uint64_t> seen;
    uint64_t none = 0;
    for (uint64_t k = 0; k < kDraws; ++k) {
      BidirectionalPlan plan;
      if (!drawBidirectionalPlan(c.n, c.deletable, c.lengths, streamKey(91, k, 0), 0, plan)) {
        ++none;
        continue;
      }
      const PlanKey key{plan.l, plan.m, plan.added, plan.eyeSide};
      ASSERT_TRUE(p.count(key)) << "n " << c.n << ": drew a plan of probability 0";
      ++seen[key];
    }
    // Chi-square over the plans (those expected fewer than 5 times pooled) and "no plan".
    double statistic = 0, pooledExpected = 0, pooledObserved = 0;
    int cells = 0;
    auto add = [&](double expected, double observed) {
      statistic += (observed - expected) * (observed - expected) / expected;
      ++cells;
    };
    for (const auto& [key, prob] : p) {
      const double expected = prob * kDraws, observed = double(seen[key]);
      if (expected < 5) {
        pooledExpected += expected, pooledObserved += observed;
        continue;
      }
      add(expected, observed);
    }
    const double noneExpected = (1 - total) * kDraws;
    if (noneExpected >= 5) add(noneExpected, double(none));
    else pooledExpected += noneExpected, pooledObserved += double(none);
    if (pooledExpected >= 5) add(pooledExpected, pooledObserved);
    else EXPECT_LE(pooledObserved, 5 + 5 * pooledExpected);
    const double pValue = test::chiSquarePValue(statistic, std::max(1, cells - 1));
    std::printf("n %d: %zu plans, chi^2 %.1f over %d cells, p %.3f\n", c.n, p.size(), statistic, cells, pValue);
    EXPECT_GT(pValue, 1e-4) << "n " << c.n;
  }
}

// The stated densities of a diffuse scene (vertex j of `path`, the test's own arithmetic):
// eye side from vertex j - 1, light side from vertex j + 1 (or the light point itself).
struct DiffuseDensities {
  const ErptWorld& w;
  double lightArea(int emitter) const {
    double a = 0;
    for (uint32_t p = 0; p < w.scene.worldPrimitiveCount(); ++p)
      if (w.scene.emitterOf(p) == emitter) a += double(w.scene.primitiveArea(p));
    return a;
  }
  // Lights are picked by power: area x luminance of their radiance.
  double pickProbability(int emitter) const {
    double total = 0, own = 0;
    for (size_t e = 0; e < w.scene.emitters.size(); ++e) {
      const double power = lightArea(int(e)) * double(luminance(w.scene.emitters[e].radiance));
      total += power;
      if (int(e) == emitter) own = power;
    }
    return own / total;
  }
  // Solid-angle density of cosine sampling around `normal` from a towards b, as an area
  // density at b.
  static double cosineToArea(const PathVertex& a, Vec3 normal, const PathVertex& b) {
    const Vec3 d = b.p - a.p;
    const double d2 = double(dot(d, d)), dist = std::sqrt(d2);
    const double cosA = std::max(0.0, double(dot(normal, d)) / dist), cosB = std::abs(double(dot(b.ng, d))) / dist;
    return cosA / kPi * cosB / d2;
  }
  double eye(const PathVertex* path, int j) const {
    if (j == 1) return 1.0 / (double(w.width) * double(w.height));
    const PathVertex& a = path[j - 1];
    const Vec3 n = dot(a.ns, path[j - 2].p - a.p) > 0 ? a.ns : -a.ns;  // the side the walk came from
    return cosineToArea(a, n, path[j]);
  }
  double light(const PathVertex* path, int n, int j, bool replaced) const {
    if (j == n - 1) return replaced ? pickProbability(path[j].emitter) / lightArea(path[j].emitter) : 0.0;
    const PathVertex& a = path[j + 1];
    if (j + 1 == n - 1) return cosineToArea(a, a.ng, path[j]);
    const Vec3 n2 = dot(a.ns, path[j + 2].p - a.p) > 0 ? a.ns : -a.ns;
    return cosineToArea(a, n2, path[j]);
  }
  double deletion(int n, bool deletable, int l, int m) const {
    const int mMax = deletable ? n : n - 1;
    auto weight = [](int kd) { return kd == 1 ? 0.25 : kd == 2 ? 0.5 : std::pow(0.5, kd); };
    auto positions = [&](int kd) { return std::max(0, std::min(n - 2, mMax - kd) + 1); };
    double z = 0;
    for (int kd = 1; kd <= mMax; ++kd) z += positions(kd) > 0 ? weight(kd) : 0.0;
    return weight(m - l) / z / positions(m - l);
  }
  double addition(int n, VertexRange lengths, int l, int m, int added) const {
    const int kept = n - (m - l - 1), deleted = m - l - 1;
    const int lo = std::max((l == 0 ? 1 : 0) + (m == n ? 1 : 0), lengths.min - kept), hi = lengths.max - kept;
    double z = 0;
    for (int a = lo; a <= hi; ++a) z += std::pow(0.5, std::abs(a - deleted));
    return std::pow(0.5, std::abs(added - deleted)) / z;
  }
  // T(y -> z) for the plan (l, m, added).
  double transition(VertexRange lengths, const PathVertex* y, int ny, int l, int m, const PathVertex* z, int nz,
                    int added) const {
    const bool replaced = m == ny;
    const bool deletable = y[ny - 1].kind == kLightVertex;
    double sum = 0;
    const int tMin = l == 0 ? 1 : 0, tMax = added - (replaced ? 1 : 0);
    for (int t = tMin; t <= tMax; ++t) {
      double p = 1;
      for (int i = 1; i <= t; ++i) p *= eye(z, l + i);
      for (int i = t + 1; i <= added; ++i) p *= light(z, nz, l + i, replaced);
      sum += p;
    }
    return deletion(ny, deletable, l, m) * addition(ny, lengths, l, m, added) * sum / (tMax - tMin + 1);
  }
};

struct Move {
  std::vector<PathVertex> y, z;
  float yFilmX, yFilmY, zFilmX, zFilmY;
  BidirectionalPlan plan;
};

// The complete bidirectional proposals of chains started at the world's seeds.
std::vector<Move> proposeMoves(const ErptWorld& w, VertexRange lengths, size_t chains) {
  StepConfig ctx = w.stepContext(MutationStrategy::Paper);
  ctx.settings.bidirectional = 1;
  ctx.lengths = lengths;
  ChainQueues q(chains);
  const size_t loaded = q.loadSeeds(w, 10, 1.0f, 4, std::max<size_t>(1, w.seeds.size() / chains) | 1);
  EXPECT_GT(loaded, chains / 2);
  q.propose(w, ctx);
  std::vector<Move> moves;
  for (size_t i = 0; i < loaded; ++i) {
    const ProposalQueue& p = q.proposals;
    EXPECT_EQ(p.mutation[i], uint8_t(MutationKind::Bidirectional));
    if (p.state[i] != kProposalComplete) continue;
    Move mv;
    const int ny = q.chains.vertexCount[i], nz = p.vertexCount[i];
    for (int j = 0; j < ny; ++j) mv.y.push_back(loadPathVertex(q.chainVertices, i * kMaxChainVertices + size_t(j)));
    for (int j = 0; j < nz; ++j) mv.z.push_back(loadPathVertex(q.proposalVertices, i * kMaxChainVertices + size_t(j)));
    mv.yFilmX = q.chains.filmX[i], mv.yFilmY = q.chains.filmY[i];
    mv.zFilmX = p.filmX[i], mv.zFilmY = p.filmY[i];
    mv.plan.l = p.regenFirst[i] - 1;
    mv.plan.added = p.regenLast[i] - mv.plan.l;
    mv.plan.m = mv.plan.l + 1 + (ny - nz + mv.plan.added);
    mv.plan.eyeSide = p.connectTo[i] - mv.plan.l;
    moves.push_back(mv);
  }
  return moves;
}

BidirectionalPlan reverseOf(const BidirectionalPlan& p) {
  BidirectionalPlan r;
  r.l = p.l;
  r.m = p.l + p.added + 1;
  r.added = p.deleted();
  return r;
}

double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[size_t(double(v.size() - 1) * q)];
}

TEST(BidirectionalMutation, DetailedBalanceWithWrittenOutDensitiesOnTheCornellBox) {
  const ErptWorld w(test::sharedScenesDir() + "/cornell-box/scene.xml", 45, 4, FilterKind::Box);
  const VertexRange lengths{2, 10};
  const std::vector<Move> moves = proposeMoves(w, lengths, 4096);
  const MeasureContext mc = w.measure();
  const DiffuseDensities stated{w};
  std::vector<double> errors;
  int lengthChanges = 0, lightReplaced = 0, filmMoved = 0;
  for (const Move& mv : moves) {
    const int ny = int(mv.y.size()), nz = int(mv.z.size());
    const BidirectionalPlan back = reverseOf(mv.plan);
    const double qf = std::min(1.0, bidirectionalRatio(mc, lengths, mv.y.data(), ny, mv.yFilmX, mv.yFilmY, mv.z.data(),
                                                       nz, mv.zFilmX, mv.zFilmY, mv.plan));
    const double qb = std::min(1.0, bidirectionalRatio(mc, lengths, mv.z.data(), nz, mv.zFilmX, mv.zFilmY, mv.y.data(),
                                                       ny, mv.yFilmX, mv.yFilmY, back));
    const double fy = luminance(bidirectionalContribution(mc, mv.y.data(), ny, mv.yFilmX, mv.yFilmY));
    const double fz = luminance(bidirectionalContribution(mc, mv.z.data(), nz, mv.zFilmX, mv.zFilmY));
    const double tyz = stated.transition(lengths, mv.y.data(), ny, mv.plan.l, mv.plan.m, mv.z.data(), nz, mv.plan.added);
    const double tzy = stated.transition(lengths, mv.z.data(), nz, back.l, back.m, mv.y.data(), ny, back.added);
    ASSERT_GT(qf, 0);
    ASSERT_GT(qb, 0) << "a valid move whose reverse is impossible";
    errors.push_back(std::abs(fy * tyz * qf / (fz * tzy * qb) - 1));
    if (getenv("DEBUG_BIDIR") && errors.back() > 1e-3)
      std::printf("ny %d nz %d l %d m %d added %d t %d: err %.3g  tyz %.3g lib %.3g  tzy %.3g lib %.3g\n", ny, nz,
                  mv.plan.l, mv.plan.m, mv.plan.added, mv.plan.eyeSide, errors.back(), tyz,
                  bidirectionalTransition(mc, lengths, mv.y.data(), ny, mv.plan.l, mv.plan.m, mv.z.data(), nz, mv.plan.added),
                  tzy, bidirectionalTransition(mc, lengths, mv.z.data(), nz, back.l, back.m, mv.y.data(), ny, back.added));
    lengthChanges += ny != nz;
    lightReplaced += mv.plan.m == ny;
    filmMoved += mv.plan.l == 0;
  }
  std::printf("%zu moves (%d change the length, %d replace the light, %d move the film position); |flow ratio - 1| "
              "median %.2e, 90%% %.2e\n",
              moves.size(), lengthChanges, lightReplaced, filmMoved, quantile(errors, 0.5), quantile(errors, 0.9));
  ASSERT_GE(moves.size(), 200u);
  EXPECT_GE(lengthChanges, 50);
  EXPECT_GE(lightReplaced, 20);
  EXPECT_GE(filmMoved, 20);
  EXPECT_LT(quantile(errors, 0.5), 1e-4);
  EXPECT_LT(quantile(errors, 0.9), 1e-3);
}

TEST(BidirectionalMutation, ReverseRatioIsTheReciprocalThroughSpecularVertices) {
  const ErptWorld w(test::sourceDir() + "/scenes/default/scene.xml", 45, 4, FilterKind::Box);
  const VertexRange lengths{2, 12};
  const std::vector<Move> moves = proposeMoves(w, lengths, 4096);
  const MeasureContext mc = w.measure();
  std::vector<double> errors;
  int throughSpecular = 0;
  for (const Move& mv : moves) {
    const int ny = int(mv.y.size()), nz = int(mv.z.size());
    const double rf = bidirectionalRatio(mc, lengths, mv.y.data(), ny, mv.yFilmX, mv.yFilmY, mv.z.data(), nz, mv.zFilmX,
                                         mv.zFilmY, mv.plan);
    const double rb = bidirectionalRatio(mc, lengths, mv.z.data(), nz, mv.zFilmX, mv.zFilmY, mv.y.data(), ny, mv.yFilmX,
                                         mv.yFilmY, reverseOf(mv.plan));
    ASSERT_GT(rb, 0);
    errors.push_back(std::abs(rf * rb - 1));
    for (const PathVertex& v : mv.z) throughSpecular += v.kind == kSpecularVertex;
  }
  std::printf("%zu moves, %d specular vertices in the proposals; |r(y->z) r(z->y) - 1| median %.2e, 90%% %.2e\n",
              moves.size(), throughSpecular, quantile(errors, 0.5), quantile(errors, 0.9));
  ASSERT_GE(moves.size(), 200u);
  EXPECT_GE(throughSpecular, 20);
  EXPECT_LT(quantile(errors, 0.9), 1e-4);
}

}  // namespace
}  // namespace erpt
