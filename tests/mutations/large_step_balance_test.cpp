// Detailed balance of MLT's large step, as ErptDetailedBalance checks the perturbations: for
// pairs of paths (y, z) the path tracer made, a chain at y gets z as a large-step proposal (as
// stageMltLargeSteps writes it) and a chain at z gets y, and the library's accept stage
// decides both. The flow must balance,
//   f(y) q(z) a(y -> z) = f(z) q(y) a(z -> y),
// with f the lens perturbation's contribution (the target the chains' perturbations keep) and
// the large step's density q computed here from what the path tracer recorded with each path,
// not from large_step.cpp: the film density H(x) / pixels of its camera sample, the BSDF
// densities stored with every vertex (pdfForward, solid angle) times the area factors
// cos / d^2, the light density of the next-event technique (pLight), and the large step's
// mixture P(n) [P(hit | n) p_hit + P(nee | n) p_nee]. Paths whose lens measure is not the area
// measure after vertex 1 (vertex 1 or 2 specular) and paths reaching the roulette depth (their
// other technique's survival is not recorded) are left out; LargeStepDensity covers those.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "stages/mlt_stages.h"
#include "core/rng.h"
#include "support/erpt_world.h"
#include "support/test_support.h"

namespace erpt {
namespace {

using test::ErptWorld;

// cos at `to` / d^2 (a point light: 1 / d^2; the environment: 1).
double areaFactor(const MeasureContext& c, const PathVertex& from, const PathVertex& to) {
  if (to.kind == kEnvironmentVertex) return 1.0;
  const Vec3 d = to.p - from.p;
  const double d2 = double(dot(d, d));
  if (to.emitter >= 0 && c.scene.emitters[size_t(to.emitter)].kind == EmitterKind::Point) return 1.0 / d2;
  return std::abs(double(dot(to.ng, d))) / (d2 * std::sqrt(d2));
}

// The large step's density of seed s from the path tracer's records (see the file comment).
double recordedDensity(const ErptWorld& w, const LargeStepModel& m, size_t s) {
  const MeasureContext c = w.measure();
  PathVertex x[kMaxChainVertices];
  const int n = w.seedPath(s, x);
  const SeedQueue& q = w.seeds.seeds;
  const VertexQueue& v = w.seeds.vertices;
  const size_t b = q.vertexBegin[s];
  double common = double(w.density->density(q.filmX[s], q.filmY[s])) / (double(w.width) * w.height);
  for (int j = 1; j < n - 2; ++j) common *= double(v.pdfForward[b + size_t(j)]) * areaFactor(c, x[j], x[j + 1]);
  common *= double(q.pLength[s]);
  const bool pointLight = x[n - 1].emitter >= 0 && c.scene.emitters[size_t(x[n - 1].emitter)].kind == EmitterKind::Point;
  // Both techniques' last vertex: the BSDF's density of the last segment (stored with vertex
  // n - 2 for either technique) and the light's; a point light cannot be hit, a pure
  // specular vertex cannot connect.
  const double pHit = n == 2 ? 1.0 : pointLight ? 0.0 : double(v.pdfForward[b + size_t(n - 2)]) * areaFactor(c, x[n - 2], x[n - 1]);
  const double pNee = n == 2 || x[n - 2].kind == kSpecularVertex ? 0.0 : double(q.pLight[s]);
  const double pn = m.neeProbability(n);
  return common * double(m.lengthProbability[n]) * ((1 - pn) * pHit + pn * pNee);
}

struct Candidate {
  size_t seed;
  double f, q;  // lum(f) in the lens measure, the recorded large-step density
};

// Loads a chain at seed `y` in `slot` and gives it seed `z` as its large-step proposal.
void setUpPair(const ErptWorld& w, const StepConfig& ctx, StepQueues& q, size_t slot, size_t y, size_t z) {
  loadChainFromSeed(q.chains, q.chainVertices, slot, w.seeds, y, streamKey(7, slot, 0), 10, 1.0f);
  PathVertex path[kMaxChainVertices];
  uint8_t kinds[kMaxChainVertices];
  const int n = w.seedPath(z, path);
  for (int j = 0; j < n; ++j) {
    storePathVertex(q.proposalVertices, slot * kMaxChainVertices + size_t(j), path[j]);
    kinds[j] = path[j].kind;
  }
  const SeedQueue& s = w.seeds.seeds;
  resetProposal(q.chains, q.proposals, q.rays, slot);
  q.proposals.mutation[slot] = uint8_t(MutationKind::LargeStep);
  q.proposals.vertexCount[slot] = uint8_t(n);
  q.proposals.signature[slot] = packSignature(kinds, n);
  q.proposals.filmX[slot] = s.filmX[z];
  q.proposals.filmY[slot] = s.filmY[z];
  const Color c = w.seeds.contribution(z);
  q.proposals.colorSet(slot, c / luminance(c));
  q.proposals.largeWeight[slot] = mltDomainWeight(ctx, path, n, s.filmX[z], s.filmY[z]);
  q.proposals.state[slot] = kProposalComplete;
}

void expectLargeStepBalances(const ErptWorld& w, const char* name) {
  LargeStepModel model;
  model.minVertices = 2;
  // A length distribution far from uniform, so that P(n) does not cancel between lengths.
  const double energy[kMaxChainVertices + 1] = {0, 0, 5, 40, 20, 3, 1, 0.5, 0.2, 0.1, 0.05, 0.02, 0.01};
  const double nee[kMaxChainVertices + 1] = {0, 0, 0, 36, 4, 2, 0.5, 0.1, 0.1, 0.08, 0.01, 0.01, 0.005};
  model.setLengths(energy, nee);
  StepConfig ctx = w.stepContext(MutationStrategy::Paper);
  ctx.settings.expectedDeposit = true;
  ctx.largeSteps = &model;
  std::vector<Candidate> paths;
  PathVertex x[kMaxChainVertices];
  for (size_t s = 0; s < w.seeds.size(); ++s) {
    if (w.seeds.seeds.vertexCount[s] > uint32_t(kMaxChainVertices)) continue;
    const int n = w.seedPath(s, x);
    if (n - 2 >= model.rrDepth || (n > 2 && x[1].kind == kSpecularVertex) || (n > 3 && x[2].kind == kSpecularVertex))
      continue;
    if (!(mltDomainWeight(ctx, x, n, w.seeds.seeds.filmX[s], w.seeds.seeds.filmY[s]) > 0)) continue;
    const double f = luminance(lensContribution(w.measure(), x, n, w.seeds.seeds.filmX[s], w.seeds.seeds.filmY[s]));
    paths.push_back({s, f, recordedDensity(w, model, s)});
  }
  ASSERT_GT(paths.size(), 1000u) << name;
  const size_t pairs = 2000;
  StepQueues q(2 * pairs);
  std::vector<std::pair<size_t, size_t>> chosen;
  for (size_t k = 0; k < pairs; ++k) {
    const size_t a = size_t(uniformFloat(streamKey(11, k, 0), 0) * float(paths.size()));
    const size_t b = size_t(uniformFloat(streamKey(11, k, 0), 1) * float(paths.size()));
    chosen.emplace_back(a, b);
    setUpPair(w, ctx, q, 2 * k, paths[a].seed, paths[b].seed);
    setUpPair(w, ctx, q, 2 * k + 1, paths[b].seed, paths[a].seed);
  }
  StepCounters counters;
  stageChainAccept(ctx, q.chains, q.chainVertices, q.proposals, q.proposalVertices, q.deposits, counters,
                  IndexRange{0, 2 * pairs});
  std::vector<double> errors;
  size_t lengthsDiffer = 0;
  for (size_t k = 0; k < pairs; ++k) {
    const Candidate& y = paths[chosen[k].first];
    const Candidate& z = paths[chosen[k].second];
    const double forward = y.f * z.q * double(q.proposals.acceptance[2 * k]);
    const double backward = z.f * y.q * double(q.proposals.acceptance[2 * k + 1]);
    ASSERT_GT(forward + backward, 0) << name << ": pair " << k << " never moves";
    errors.push_back(std::abs(forward - backward) / std::max(forward, backward));
    lengthsDiffer += w.seeds.seeds.vertexCount[y.seed] != w.seeds.seeds.vertexCount[z.seed];
  }
  std::sort(errors.begin(), errors.end());
  const double median = errors[errors.size() / 2], p90 = errors[errors.size() * 9 / 10];
  std::printf("%s: %zu pairs (%zu of different lengths), relative imbalance median %.2g, 90%% %.2g, 99%% %.2g\n", name,
              pairs, lengthsDiffer, median, p90, errors[errors.size() * 99 / 100]);
  EXPECT_GT(lengthsDiffer, pairs / 5);
  // The recorded densities belong to the directions the path tracer sampled, f here to the
  // directions between the stored (rounded) vertices: measured medians 1e-7 to 4e-5, 90%
  // below 5e-4. Dropping P(n) from W, or the next-event technique from q, made the median
  // 0.3-0.46 and the 90% quantile 0.6-0.9 on every scene here.
  EXPECT_LT(median, 1e-4) << name;
  EXPECT_LT(p90, 1e-3) << name;
}

TEST(MltDetailedBalance, LargeStepOnCornellBox) {
  const ErptWorld w(test::sharedScenesDir() + "/cornell-box/scene.xml", 32, 8, FilterKind::Box);
  expectLargeStepBalances(w, "cornell box");
}

TEST(MltDetailedBalance, LargeStepOnGlassAndMirrorSpheres) {
  const ErptWorld w(test::sourceDir() + "/scenes/default/scene.xml", 32, 8, FilterKind::Tent);
  expectLargeStepBalances(w, "default scene");
}

TEST(MltDetailedBalance, LargeStepWithSphereAndSpotLights) {
  const ErptWorld spheres(test::sourceDir() + "/tests/data/sphere-lights.xml", 32, 8, FilterKind::Box);
  expectLargeStepBalances(spheres, "sphere lights");
  const ErptWorld spot(test::sourceDir() + "/tests/data/spot-caustic.xml", 32, 8, FilterKind::Box);
  expectLargeStepBalances(spot, "spot caustic");
}

}  // namespace
}  // namespace erpt
