// The lens contribution packet (mutations/lens_contribution_packet.h) against the scalar unit,
// slot by slot, over several chain steps: every proposal the packet takes must get the f(z)
// that lensContribution gives for the same path, up to rounding, and the packet must take the
// shapes it is for and leave the others. The room has every case: two-sided walls, a one-sided
// panel seen from both sides (its back has no diffuse lobe), a one-sided light seen from behind,
// a textured box and a plastic sphere (the packet leaves both to the unit).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "mutations/lens_contribution_packet.h"
#include "support/diffuse_room.h"
#include "support/erpt_world.h"
#include "support/slot_differences.h"
#include "support/test_support.h"

namespace erpt {
namespace {

const std::string kScene = std::string(R"(<scene version="3.0.0">
  <sensor type="perspective">
    <float name="fov" value="70"/>
    <transform name="to_world"><lookat origin="0, 0, 1.8" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="61"/><integer name="height" value="61"/></film>
  </sensor>
)") + test::kDiffuseRoomWalls + R"(
  <shape type="rectangle">
    <bsdf type="diffuse"><rgb name="reflectance" value="0.4 0.4 0.9"/></bsdf>
    <transform name="to_world"><scale value="0.7"/><rotate y="1" angle="160"/><translate x="-0.6" y="-0.3"/></transform>
  </shape>
  <shape type="cube">
    <bsdf type="diffuse">
      <texture type="checkerboard" name="reflectance"><rgb name="color0" value="0.8 0.6 0.4"/><rgb name="color1" value="0.2"/></texture>
    </bsdf>
    <transform name="to_world"><scale value="0.3"/><translate x="0.8" y="-1.4" z="-0.8"/></transform>
  </shape>
  <shape type="sphere">
    <point name="center" x="-0.3" y="-1.5" z="-0.5"/><float name="radius" value="0.4"/>
    <bsdf type="plastic"/>
  </shape>
  <shape type="rectangle">
    <emitter type="area"><rgb name="radiance" value="8 8 8"/></emitter>
    <transform name="to_world"><scale value="0.5"/><rotate x="1" angle="80"/><translate y="1.6"/></transform>
  </shape>
</scene>)";

using test::quantile;
using test::relativeDifference;

TEST(LensContributionPacket, MatchesTheScalarUnitSlotBySlot) {
  test::TempDir dir;
  const test::ErptWorld w(dir.write("room.xml", kScene), 61, 4, FilterKind::Tent);
  const StepConfig ctx = w.stepContext(MutationStrategy::LensOnly);
  test::ChainQueues q(3001);  // not a multiple of the packet or of any vector width
  // Seeds spread over the whole store, which holds them by length: paths of every length.
  const size_t chains = q.loadSeeds(w, 50, 0.01f, 7, w.seeds.size() / 3001);
  ASSERT_GT(chains, 2000u);

  size_t complete = 0, taken = 0, viaLight = 0, zero = 0, zeroDiffer = 0, declined = 0;
  std::vector<double> error;
  StepCounters counters;
  for (int step = 0; step < 6; ++step) {
    q.propose(w, ctx);
    const size_t n = q.chains.size();
    LensContributionPacket packet;
    for (size_t begin = 0; begin < n; begin += LensContributionPacket::kCapacity) {
      const size_t count = std::min(LensContributionPacket::kCapacity, n - begin);
      packet.evaluate(ctx, q.chains, q.chainVertices, q.proposals, q.proposalVertices, begin, count);
      for (size_t i = begin; i < begin + count; ++i) {
        if (q.chains.stepsLeft[i] == 0 || q.proposals.state[i] != kProposalComplete) {
          EXPECT_FALSE(packet.took(i)) << "slot " << i;
          continue;
        }
        ++complete;
        // z as the scalar unit sees it: the current path with the proposal's vertex 1.
        PathVertex z[kMaxChainVertices];
        const int nz = loadChainPath(q.chains, q.chainVertices, i, z);
        const int first = q.proposals.regenFirst[i], last = q.proposals.regenLast[i];
        for (int j = first; j <= last; ++j)
          loadPathVertex(q.proposalVertices, i * kMaxChainVertices + size_t(j), z[j]);
        if (!packet.took(i)) {
          ++declined;
          continue;
        }
        ++taken;
        EXPECT_EQ(first, 1);
        EXPECT_EQ(last, 1);
        viaLight += z[2].kind == kLightVertex;
        // The unit with the chain's cached tail, exactly as the accept stage would call it.
        FixedTail tail;
        if (q.chains.tailKind[i] == uint8_t(MutationKind::Lens)) tail = FixedTail{q.chains.tailAt(i), true};
        const Color scalar = lensContribution(w.measure(), z, nz, q.proposals.filmX[i], q.proposals.filmY[i], &tail);
        const Color lanes = packet.fz(i);
        const bool scalarZero = !(luminance(scalar) > 0), lanesZero = !(luminance(lanes) > 0);
        zero += scalarZero;
        zeroDiffer += scalarZero != lanesZero;
        if (!scalarZero && !lanesZero) error.push_back(relativeDifference(lanes, scalar, 1e-30f));
      }
    }
    // Advance the chains (and fill their caches) with the library's accept stage.
    stageChainAccept(ctx, q.chains, q.chainVertices, q.proposals, q.proposalVertices, q.deposits, counters,
                     {0, n});
  }
  std::printf("complete %zu, taken %zu (through the light %zu, zero %zu), declined %zu; zero decisions differ %zu; "
              "relative difference median %.2g, 99%% %.2g\n",
              complete, taken, viaLight, zero, declined, zeroDiffer, quantile(error, 0.5), quantile(error, 0.99));
  // Every case in numbers: both shapes, zero and non-zero f, and proposals left to the unit
  // (the first step of every chain, the textured box, the plastic sphere).
  EXPECT_GT(taken, complete / 3);
  EXPECT_GT(declined, complete / 20);
  EXPECT_GT(viaLight, taken / 50);
  EXPECT_GT(taken - viaLight, taken / 2);
  EXPECT_GT(zero, taken / 100);
  EXPECT_LE(zeroDiffer, taken / 1000);
  EXPECT_LT(quantile(error, 0.5), 1e-6);
  EXPECT_LT(quantile(error, 0.99), 1e-4);
}

}  // namespace
}  // namespace erpt
