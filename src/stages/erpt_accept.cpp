// ERPT accept stage: acceptance probability from the path contributions in the mutation's
// measure, the Metropolis decision, the step's deposits (equal deposition: every step of
// every chain deposits e_d; detailed balance: expected values of e / m), and the chain update.
#include <algorithm>
#include <cmath>

#include "erpt/erpt_stages.h"
#include "erpt/rng.h"

namespace erpt {

namespace {

// Vertices [1, last] of a complete proposal were regenerated; the rest are the chain's.
int lastRegenerated(MutationKind kind, const uint8_t* kinds, int n, int connectTo) {
  if (kind == MutationKind::Caustic) return causticSource(kinds, n) - 1;
  return connectTo > 0 ? connectTo - 1 : n - 1;
}

void writeDeposit(DepositQueue& d, size_t i, int which, float x, float y, Color c) {
  if (which == 0) {
    d.x0[i] = x, d.y0[i] = y, d.r0[i] = c.x, d.g0[i] = c.y, d.b0[i] = c.z;
  } else {
    d.x1[i] = x, d.y1[i] = y, d.r1[i] = c.x, d.g1[i] = c.y, d.b1[i] = c.z;
  }
}

}  // namespace

void stageErptAccept(const ErptStepContext& ctx, ChainQueue& chains, VertexQueue& chainVertices,
                     ProposalQueue& proposals, const VertexQueue& proposalVertices, DepositQueue& deposits,
                     ErptCounters& counters, IndexRange range) {
  PathVertex y[kMaxChainVertices], z[kMaxChainVertices];
  uint64_t proposed[kMutationKindCount] = {}, accepted[kMutationKindCount] = {}, rejected[kRejectReasonCount] = {};
  for (size_t i = range.begin; i < range.end; ++i) {
    writeDeposit(deposits, i, 0, 0, 0, Color(0.0f));
    writeDeposit(deposits, i, 1, 0, 0, Color(0.0f));
    if (chains.stepsLeft[i] == 0) continue;
    const int n = chains.vertexCount[i];
    uint8_t kinds[kMaxChainVertices];
    unpackSignature(chains.signature[i], n, kinds);
    const MutationKind kind = MutationKind(proposals.mutation[i]);
    const size_t base = i * kMaxChainVertices;
    float q = 0;
    int last = 0;
    Color fz(0.0f);
    float fzLum = 0;
    if (proposals.state[i] == kProposalComplete) {
      // With the fixed tail cached, f only reads the vertices up to where the tail starts.
      FixedTail tail;
      if (chains.tailKind[i] == uint8_t(kind)) tail = FixedTail{Color(chains.tailR[i], chains.tailG[i], chains.tailB[i]), true};
      const int needed = tail.known ? std::min(n, tailStart(kind, kinds, n) + 1) : n;
      for (int j = 0; j < needed; ++j) y[j] = loadVertex(chainVertices, base + size_t(j));
      for (int j = needed; j < n; ++j) y[j].kind = kinds[j];
      last = lastRegenerated(kind, kinds, n, proposals.connectTo[i]);
      for (int j = 0; j < n; ++j) z[j] = j >= 1 && j <= last ? loadVertex(proposalVertices, base + size_t(j)) : y[j];
      fz = contributionFor(kind, ctx.measure, z, n, proposals.filmX[i], proposals.filmY[i], &tail);
      if (tail.known) {
        chains.tailR[i] = tail.value.x;
        chains.tailG[i] = tail.value.y;
        chains.tailB[i] = tail.value.z;
        chains.tailKind[i] = uint8_t(kind);
      }
      const float lz = luminance(fz);
      if (lz > 0 && std::isfinite(lz)) {
        // f(y) in this mutation's measure: cached from the step that made y current, if it
        // used the same mutation (always, under the paper's strategy).
        if (chains.fKind[i] != uint8_t(kind)) {
          chains.fLum[i] =
              luminance(contributionFor(kind, ctx.measure, y, n, chains.filmX[i], chains.filmY[i], &tail));
          chains.fKind[i] = uint8_t(kind);
        }
        const float ly = chains.fLum[i];
        if (ly > 0 && std::isfinite(ly)) {
          q = std::min(1.0f, lz / ly);
          fz = fz / lz;
          fzLum = lz;
        } else {
          // A chain must never stand on a path of zero density in the mutation's measure (it
          // would accept everything); seeds are checked when chains start, this is the guard.
          proposals.reason[i] = kRejectCurrentZero;
        }
      } else {
        proposals.reason[i] = kRejectZero;
      }
    }
    proposals.acceptance[i] = q;
    const bool accept = uniformFloat(chains.key[i], stepDim(chains.step[i], kDimAccept)) < q;
    if (q > 0 && !accept) proposals.reason[i] = kRejectByChance;
    ++proposed[size_t(kind)];
    if (accept)
      ++accepted[size_t(kind)];
    else
      ++rejected[proposals.reason[i]];

    const Color colorY{chains.colorR[i], chains.colorG[i], chains.colorB[i]};
    const float ed = chains.energy[i];
    // Detailed balance (section 3.1): the mutation receives e q / m, the rest stays at x,
    // and x never moves; the deposits are the expected-value ones with e / m per step.
    const bool detailedBalance = ctx.flow == FlowRule::DetailedBalance;
    if (ctx.expectedDeposit || detailedBalance) {
      writeDeposit(deposits, i, 0, chains.filmX[i], chains.filmY[i], colorY * (ed * (1 - q)));
      if (q > 0) writeDeposit(deposits, i, 1, proposals.filmX[i], proposals.filmY[i], fz * (ed * q));
    }
    if (accept && !detailedBalance) {
      for (int j = 1; j <= last; ++j) chainVertices.copyRow(base + size_t(j), proposalVertices, base + size_t(j));
      chains.filmX[i] = proposals.filmX[i];
      chains.filmY[i] = proposals.filmY[i];
      chains.colorR[i] = fz.x;
      chains.colorG[i] = fz.y;
      chains.colorB[i] = fz.z;
      chains.fLum[i] = fzLum;
      chains.fKind[i] = uint8_t(kind);
      // Another mutation's cached tail may include vertices this one moved.
      if (chains.tailKind[i] != uint8_t(kind)) chains.tailKind[i] = uint8_t(MutationKind::None);
    }
    if (!ctx.expectedDeposit && !detailedBalance)
      writeDeposit(deposits, i, 0, chains.filmX[i], chains.filmY[i],
                   Color(chains.colorR[i], chains.colorG[i], chains.colorB[i]) * ed);
    ++chains.step[i];
    --chains.stepsLeft[i];
  }
  for (int k = 0; k < kMutationKindCount; ++k) {
    counters.proposed[k] += proposed[k];
    counters.accepted[k] += accepted[k];
  }
  for (int r = 0; r < kRejectReasonCount; ++r) counters.rejected[r] += rejected[r];
}

}  // namespace erpt
