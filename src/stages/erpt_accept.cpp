// ERPT accept stage: the acceptance probability from the path contributions in the mutation's
// measure and its ratio of transition densities, the Metropolis coin, the step's deposit
// records (the rule lives in erpt_deposit.cpp), and the chain update.
#include <algorithm>
#include <cmath>

#include "erpt/erpt_stages.h"
#include "erpt/large_step.h"
#include "erpt/rng.h"

namespace erpt {

namespace {
uint8_t measureOf(MutationKind kind) { return uint8_t(mutationOf(kind).measure); }

// MLT's large step: q = min(1, W(z) / W(y)) (large_step.h; its proposal density does not
// depend on y). W(y) is cached with the chain until a perturbation moves it.
float largeStepAcceptance(const ErptStepContext& ctx, ChainQueue& chains, const VertexQueue& chainVertices,
                          ProposalQueue& proposals, size_t i) {
  if (chains.largeWeight[i] < 0) {
    PathVertex y[kMaxChainVertices];
    const int n = loadChainPath(chains, chainVertices, i, y);
    chains.largeWeight[i] = largeStepWeight(ctx.measure, *ctx.largeSteps, y, n);
  }
  const float wy = chains.largeWeight[i], wz = proposals.largeWeight[i];
  if (!(wy > 0) || !std::isfinite(wy)) {
    // q(y) = 0: no large step leads to y, so none may leave it either.
    proposals.reason[i] = kRejectIrreversible;
    return 0.0f;
  }
  return std::min(1.0f, wz / wy);
}

// Moves the chain in slot i to its large step's path: every vertex, its count and signature.
void takeLargeStep(ChainQueue& chains, VertexQueue& chainVertices, const ProposalQueue& proposals,
                   const VertexQueue& proposalVertices, size_t i) {
  const size_t base = i * kMaxChainVertices;
  for (int j = 0; j < proposals.vertexCount[i]; ++j)
    chainVertices.copyRow(base + size_t(j), proposalVertices, base + size_t(j));
  chains.vertexCount[i] = proposals.vertexCount[i];
  chains.signature[i] = proposals.signature[i];
  chains.largeWeight[i] = proposals.largeWeight[i];
  chains.fKind[i] = chains.tailKind[i] = uint8_t(MutationKind::None);  // f and the tail in no measure yet
}
}  // namespace

void stageErptAccept(const ErptStepContext& ctx, ChainQueue& chains, VertexQueue& chainVertices,
                     ProposalQueue& proposals, const VertexQueue& proposalVertices, DepositQueue& deposits,
                     ErptCounters& counters, IndexRange range) {
  PathVertex y[kMaxChainVertices], z[kMaxChainVertices];
  uint64_t proposed[kMutationKindCount] = {}, accepted[kMutationKindCount] = {}, rejected[kRejectReasonCount] = {};
  const bool moves = ctx.settings.flow != FlowRule::DetailedBalance;  // detailed balance: x never moves
  for (size_t i = range.begin; i < range.end; ++i) {
    clearStepDeposits(deposits, i);
    if (chains.stepsLeft[i] == 0) continue;
    const int n = chains.vertexCount[i];
    uint8_t kinds[kMaxChainVertices];
    unpackSignature(chains.signature[i], n, kinds);
    const MutationKind kind = MutationKind(proposals.mutation[i]);
    const size_t base = i * kMaxChainVertices;
    const int first = proposals.regenFirst[i], last = proposals.regenLast[i];
    float q = 0;
    Color fz(0.0f);
    float fzLum = 0;
    const bool large = kind == MutationKind::LargeStep;
    if (proposals.state[i] == kProposalComplete && large) {
      q = largeStepAcceptance(ctx, chains, chainVertices, proposals, i);
      fz = proposals.colorAt(i);
    } else if (proposals.state[i] == kProposalComplete) {
      const Mutation& unit = mutationOf(kind);
      const uint8_t measure = measureOf(kind);
      // With the fixed tail cached, f only reads the vertices up to where the tail starts.
      FixedTail tail;
      if (chains.tailKind[i] == measure) tail = FixedTail{chains.tailAt(i), true};
      const int needed = tail.known ? std::min(n, unit.tailStart(kinds, n) + 1) : n;
      for (int j = 0; j < needed; ++j) loadPathVertex(chainVertices, base + size_t(j), y[j]);
      for (int j = needed; j < n; ++j) y[j].kind = kinds[j];
      // z: the regenerated vertices from the proposal, the rest as y's.
      for (int j = 0; j < n; ++j) {
        if (j >= first && j <= last)
          loadPathVertex(proposalVertices, base + size_t(j), z[j]);
        else
          z[j] = y[j];
      }
      fz = unit.contribution(ctx.measure, z, n, proposals.filmX[i], proposals.filmY[i], &tail);
      if (tail.known) {
        chains.tailSet(i, tail.value);
        chains.tailKind[i] = measure;
      }
      const float lz = luminance(fz);
      if (lz > 0 && std::isfinite(lz)) {
        // f(y) in this measure: cached from the step that made y current, if it was in the
        // same measure (always, under the paper's strategy).
        if (chains.fKind[i] != measure) {
          chains.fLum[i] = luminance(unit.contribution(ctx.measure, y, n, chains.filmX[i], chains.filmY[i], &tail));
          chains.fKind[i] = measure;
        }
        const float ly = chains.fLum[i];
        const CurrentPath py{y, kinds, n, chains.filmX[i], chains.filmY[i]};
        const CurrentPath pz{z, kinds, n, proposals.filmX[i], proposals.filmY[i]};
        // T(z->y) / T(y->z), times a(z) / a(y) when the choice depends on the film position.
        const float ratio =
            unit.transitionRatio(ctx.measure, py, pz, proposals.perturbSize[i]) * proposals.selection[i];
        if (!(ly > 0) || !std::isfinite(ly)) {
          // A chain must never stand on a path of zero density in the mutation's measure (it
          // would accept everything); seeds are checked when chains start, this is the guard.
          proposals.reason[i] = kRejectCurrentZero;
        } else if (!(ratio > 0) || !std::isfinite(ratio)) {
          proposals.reason[i] = kRejectIrreversible;
        } else {
          q = std::min(1.0f, lz / ly * ratio);
          fz = fz / lz;
          fzLum = lz;
        }
      } else {
        proposals.reason[i] = kRejectZero;
      }
    }
    proposals.acceptance[i] = q;
    // 53 bits: with a 24-bit coin every q below 2^-24 would be accepted with probability 2^-24.
    const bool accept = uniformDouble(chains.key[i], stepDim(chains.step[i], kDimAccept)) < q;
    if (q > 0 && !accept) proposals.reason[i] = kRejectByChance;
    ++proposed[size_t(kind)];
    if (accept)
      ++accepted[size_t(kind)];
    else
      ++rejected[proposals.reason[i]];

    const StepDeposit before{chains.filmX[i], chains.filmY[i], chains.colorAt(i)};
    const StepDeposit proposal{proposals.filmX[i], proposals.filmY[i], fz};
    if (accept && moves && large) {
      takeLargeStep(chains, chainVertices, proposals, proposalVertices, i);
      chains.filmX[i] = proposals.filmX[i];
      chains.filmY[i] = proposals.filmY[i];
      chains.colorSet(i, fz);
    } else if (accept && moves) {
      chains.largeWeight[i] = -1;  // W(y) of the new path: computed when a large step needs it
      for (int j = first; j <= last; ++j) chainVertices.copyRow(base + size_t(j), proposalVertices, base + size_t(j));
      chains.filmX[i] = proposals.filmX[i];
      chains.filmY[i] = proposals.filmY[i];
      chains.colorSet(i, fz);
      chains.fLum[i] = fzLum;
      chains.fKind[i] = measureOf(kind);
      // A tail cached in another measure may include vertices this mutation moved.
      if (chains.tailKind[i] != chains.fKind[i]) chains.tailKind[i] = uint8_t(MutationKind::None);
    }
    writeStepDeposits(ctx.settings, before, proposal, q, accept && moves, chains.energy[i], deposits, i);
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
