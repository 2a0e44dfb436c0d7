// ERPT stage kernels on queues built by hand from path-traced seeds.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "integrators/chain_lanes.h"
#include "core/rng.h"
#include "support/erpt_world.h"
#include "support/test_support.h"

namespace erpt {
namespace {

using test::ChainQueues;
using test::ErptWorld;

std::string cornell() { return test::sharedScenesDir() + "/cornell-box/scene.xml"; }
std::string defaultScene() { return test::sourceDir() + "/scenes/default/scene.xml"; }

bool sameVertex(const VertexQueue& a, size_t i, const VertexQueue& b, size_t j) {
  return a.pX[i] == b.pX[j] && a.pY[i] == b.pY[j] && a.pZ[i] == b.pZ[j] && a.kind[i] == b.kind[j] &&
         a.material[i] == b.material[j];
}

// Accept keeps exactly the proposals whose coin flip fell below q: their regenerated vertices
// and film position replace the chain's; every other chain is left as it was.
TEST(ErptStages, AcceptKeepsExactlyTheAcceptedProposals) {
  for (const std::string& file : {cornell(), defaultScene()}) {
    ErptWorld w(file, 48, 2, FilterKind::Tent);
    ChainQueues q(2048);
    const size_t loaded = q.loadSeeds(w, 10, 1.0f, 9);
    ASSERT_GT(loaded, 1000u);
    const StepConfig ctx = w.stepContext(MutationStrategy::Mixed);
    q.propose(w, ctx);
    const float depositEnergy = 1;  // loadSeeds' energy per step
    const ChainQueue before = q.chains;
    const VertexQueue verticesBefore = q.chainVertices;
    StepCounters counters;
    stageChainAccept(ctx, q.chains, q.chainVertices, q.proposals, q.proposalVertices, q.deposits, counters,
                    IndexRange{0, q.chains.size()});
    size_t accepted = 0, rejected = 0;
    for (size_t i = 0; i < loaded; ++i) {
      const float u = uniformFloat(before.key[i], stepDim(before.step[i], kDimAccept));
      const bool shouldAccept = u < q.proposals.acceptance[i];
      const bool moved = q.chains.filmX[i] != before.filmX[i] || q.chains.filmY[i] != before.filmY[i];
      if (shouldAccept) {
        ++accepted;
        EXPECT_EQ(q.proposals.state[i], kProposalComplete);
        EXPECT_EQ(q.chains.filmX[i], q.proposals.filmX[i]);
        EXPECT_EQ(q.chains.filmY[i], q.proposals.filmY[i]);
        // Some regenerated vertex must now be the proposal's.
        bool fromProposal = false;
        for (int j = 1; j < q.chains.vertexCount[i]; ++j)
          fromProposal |= sameVertex(q.chainVertices, i * kMaxChainVertices + j, q.proposalVertices,
                                     i * kMaxChainVertices + j) &&
                          !sameVertex(verticesBefore, i * kMaxChainVertices + j, q.proposalVertices,
                                      i * kMaxChainVertices + j);
        EXPECT_TRUE(fromProposal) << "slot " << i;
      } else {
        ++rejected;
        EXPECT_FALSE(moved) << "slot " << i;
        for (int j = 0; j < q.chains.vertexCount[i]; ++j)
          EXPECT_TRUE(sameVertex(q.chainVertices, i * kMaxChainVertices + j, verticesBefore, i * kMaxChainVertices + j));
        EXPECT_EQ(q.chains.colorR[i], before.colorR[i]);
      }
      EXPECT_EQ(q.chains.stepsLeft[i], before.stepsLeft[i] - 1);
      EXPECT_EQ(q.chains.step[i], before.step[i] + 1);
      // The paper's rule: one deposit of e_d at the (possibly new) current path.
      EXPECT_EQ(q.deposits.x[i * kDepositsPerStep], q.chains.filmX[i]);
      EXPECT_NEAR(luminance(q.deposits.energyAt(i * kDepositsPerStep + 0)), depositEnergy, 1e-5);
    }
    EXPECT_GT(accepted, loaded / 10) << file;
    EXPECT_GT(rejected, loaded / 50) << file;
    uint64_t counted = 0;
    for (int k = 0; k < kMutationKindCount; ++k) counted += counters.proposed[k];
    EXPECT_EQ(counted, loaded);
  }
}

// Expected-value deposition: (1 - q) e_d at the current path and q e_d at the proposal.
TEST(ErptStages, ExpectedDepositsSplitByAcceptance) {
  ErptWorld w(defaultScene(), 32, 2, FilterKind::Box);
  ChainQueues q(1024);
  const size_t loaded = q.loadSeeds(w, 5, 0.5f, 9);
  StepConfig ctx = w.stepContext(MutationStrategy::Paper);
  ctx.settings.expectedDeposit = true;
  q.propose(w, ctx);
  const ChainQueue before = q.chains;
  StepCounters counters;
  stageChainAccept(ctx, q.chains, q.chainVertices, q.proposals, q.proposalVertices, q.deposits, counters,
                  IndexRange{0, q.chains.size()});
  for (size_t i = 0; i < loaded; ++i) {
    const float qa = q.proposals.acceptance[i];
    EXPECT_EQ(q.deposits.x[i * kDepositsPerStep], before.filmX[i]);
    EXPECT_NEAR(luminance(q.deposits.energyAt(i * kDepositsPerStep + 0)), 0.5f * (1 - qa), 1e-5);
    EXPECT_NEAR(luminance(q.deposits.energyAt(i * kDepositsPerStep + 1)), 0.5f * qa, 1e-5);
    if (qa > 0) {
      EXPECT_EQ(q.deposits.x[i * kDepositsPerStep + 1], q.proposals.filmX[i]);
    }
  }
}

// numChains = floor(U + e / (m e_d)) has expectation e / (m e_d) (stratified U: exact up to
// 1 / strata).
TEST(ErptStages, NumberOfChainsHasTheRightExpectation) {
  for (double e : {0.013, 0.7, 1.0, 3.25, 41.9}) {
    const int strata = 100000;
    double sum = 0;
    for (int k = 0; k < strata; ++k) sum += chainsForSeed(e, 10, 0.05, float((k + 0.5) / strata));
    EXPECT_NEAR(sum / strata, e / (10 * 0.05), 1e-4) << e;
  }
  EXPECT_EQ(chainsForSeed(0, 10, 1, 0.999f), 0u);
  EXPECT_EQ(chainsForSeed(20, 10, 1, 0.0f), 2u);
}

// Deposits sum exactly to chains x m x e_d (each deposit carries e_d of luminance, and the
// filter splat weights of each deposit sum to 1), and the film receives all of it.
TEST(ErptStages, DepositsSumToChainsTimesLengthTimesDepositEnergy) {
  ErptWorld w(defaultScene(), 40, 2, FilterKind::Tent);
  Film film(w.width, w.height);
  ChainStats stats;
  StageTimes times;
  StepConfig ctx = w.stepContext(MutationStrategy::Paper);
  ChainSettings lanes;
  lanes.chainLength = 7;
  lanes.directSamples = -1;  // every seed is ERPT's
  ChainLanes::Config config{ctx, lanes, 3, 512, 0.02};
  ChainLanes chains(*w.tracer, config, film, stats, times);
  chains.consume(w.seeds);
  chains.finish();
  ASSERT_GT(stats.chains, 1000u);
  // Seeds no chain can move (too long, zero f) deposit their own estimate where they are.
  const double expected = double(stats.chains) * 7 * 0.02 + chains.inPlaceEnergy();
  EXPECT_NEAR(chains.depositedEnergy() / expected, 1.0, 1e-5);
  RgbImage img = chains.image(1.0);
  double onFilm = 0;
  for (const Color& c : img.pixels) onFilm += luminance(c);
  EXPECT_NEAR(onFilm / expected, 1.0, 1e-4);
  // Every chain runs its 7 steps.
  EXPECT_EQ(stats.mutations, stats.chains * 7);
}

}  // namespace
}  // namespace erpt
