// The perturbations' acceptance and move (mutation.h): the part of the accept stage that
// every perturbation unit shares. f(z) and f(y) in the unit's measure, the fixed tail cached
// with the chain, and the units' transition ratio.
#include <algorithm>
#include <cmath>

#include "mutations/mutation.h"

namespace erpt {

namespace {

// A proposal whose f is zero or not finite in the unit's measure cannot be accepted.
bool rejectsZero(ProposalQueue& proposals, size_t i, float lz) {
  if (lz > 0 && std::isfinite(lz)) return false;
  proposals.reason[i] = kRejectZero;
  return true;
}

// q from lum(f(z)) = lz, lum(f(y)) = ly and T(z->y) / T(y->z) = ratio, times a(z) / a(y) when
// the choice depends on the film position and the measure's factor that the unit's stage
// measured (both 1 otherwise); the colour a deposit of z carries.
void decide(ProposalQueue& proposals, size_t i, float lz, float ly, float ratio, Acceptance& a) {
  ratio *= proposals.selection[i] * proposals.measureRatio[i];
  if (!(ly > 0) || !std::isfinite(ly)) {
    // A chain must never stand on a path of zero density in the mutation's measure (it would
    // accept everything); seeds are checked when chains start, this is the guard.
    proposals.reason[i] = kRejectCurrentZero;
  } else if (!(ratio > 0) || !std::isfinite(ratio)) {
    proposals.reason[i] = kRejectIrreversible;
  } else {
    a.q = std::min(1.0f, lz / ly * ratio);
    a.fz = a.fz / lz;
    a.fzLum = lz;
  }
}

}  // namespace

Acceptance perturbationAcceptance(const StepConfig& ctx, const AcceptSlot& s) {
  ChainQueue& chains = s.chains;
  ProposalQueue& proposals = s.proposals;
  const size_t i = s.i;
  PathVertex* y = s.y;
  PathVertex* z = s.z;
  const int n = chains.vertexCount[i];
  uint8_t kinds[kMaxChainVertices];
  unpackSignature(chains.signature[i], n, kinds);
  const MutationKind kind = MutationKind(proposals.mutation[i]);
  const size_t base = i * kMaxChainVertices;
  const int first = proposals.regenFirst[i], last = proposals.regenLast[i];
  Acceptance a;
  const Mutation& unit = mutationOf(kind);
  const uint8_t measure = uint8_t(unit.measure);
  // With the fixed tail cached, f only reads the vertices up to where the tail starts.
  FixedTail tail;
  if (chains.tailKind[i] == measure) tail = FixedTail{chains.tailAt(i), true};
  const int needed = tail.known ? std::min(n, unit.tailStart(kinds, n) + 1) : n;
  for (int j = 0; j < needed; ++j) loadPathVertex(s.chainVertices, base + size_t(j), y[j]);
  for (int j = needed; j < n; ++j) y[j].kind = kinds[j];
  // z: the regenerated vertices from the proposal, the rest as y's.
  for (int j = 0; j < n; ++j) {
    if (j >= first && j <= last)
      loadPathVertex(s.proposalVertices, base + size_t(j), z[j]);
    else
      z[j] = y[j];
  }
  a.fz = unit.contribution(ctx.measure, z, n, proposals.filmX[i], proposals.filmY[i], &tail);
  if (tail.known) {
    chains.tailSet(i, tail.value);
    chains.tailKind[i] = measure;
  }
  const float lz = luminance(a.fz);
  if (rejectsZero(proposals, i, lz)) return a;
  // f(y) in this measure: cached from the step that made y current, if it was in the same
  // measure (always, under the paper's strategy).
  if (chains.fKind[i] != measure) {
    chains.fLum[i] = luminance(unit.contribution(ctx.measure, y, n, chains.filmX[i], chains.filmY[i], &tail));
    chains.fKind[i] = measure;
  }
  const CurrentPath py{y, kinds, n, chains.filmX[i], chains.filmY[i]};
  const CurrentPath pz{z, kinds, n, proposals.filmX[i], proposals.filmY[i]};
  decide(proposals, i, lz, chains.fLum[i], unit.transitionRatio(ctx.measure, py, pz, proposals.perturbSize[i]), a);
  return a;
}

Acceptance perturbationAcceptanceOf(const StepConfig& ctx, const AcceptSlot& s, Color fz) {
  ChainQueue& chains = s.chains;
  ProposalQueue& proposals = s.proposals;
  const size_t i = s.i;
  const int n = chains.vertexCount[i];
  const Mutation& unit = mutationOf(MutationKind(proposals.mutation[i]));
  Acceptance a;
  a.fz = fz;
  const float lz = luminance(fz);
  if (rejectsZero(proposals, i, lz)) return a;
  // No vertices and no kinds: this unit's ratio reads the film positions only.
  const CurrentPath py{nullptr, nullptr, n, chains.filmX[i], chains.filmY[i]};
  const CurrentPath pz{nullptr, nullptr, n, proposals.filmX[i], proposals.filmY[i]};
  decide(proposals, i, lz, chains.fLum[i], unit.transitionRatio(ctx.measure, py, pz, proposals.perturbSize[i]), a);
  return a;
}

void moveToPerturbation(const AcceptSlot& s, const Acceptance& accepted) {
  ChainQueue& chains = s.chains;
  const size_t i = s.i, base = i * kMaxChainVertices;
  chains.largeWeight[i] = -1;  // W(y) of the new path: computed when a large step needs it
  for (int j = s.proposals.regenFirst[i]; j <= s.proposals.regenLast[i]; ++j)
    s.chainVertices.copyRow(base + size_t(j), s.proposalVertices, base + size_t(j));
  chains.fLum[i] = accepted.fzLum;
  chains.fKind[i] = uint8_t(mutationOf(MutationKind(s.proposals.mutation[i])).measure);
  // A tail cached in another measure may include vertices this mutation moved.
  if (chains.tailKind[i] != chains.fKind[i]) chains.tailKind[i] = uint8_t(MutationKind::None);
}

}  // namespace erpt
