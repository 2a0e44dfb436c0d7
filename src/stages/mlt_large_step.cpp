// MLT's stages in the chain step (mlt_stages.h): the choice of a large step, and the large
// steps' proposals from their path-tracer samples.
#include <cmath>
#include <vector>

#include "stages/mlt_stages.h"
#include "core/rng.h"
#include "tracer/tracer.h"

namespace erpt {

namespace {

class MltChooser final : public ProposalPolicy {
 public:
  void choose(const StepConfig& ctx, const ChainQueue& chains, ProposalQueue& proposals, RayQueue& rays,
              IndexRange range) const override {
    erptChooser().choose(ctx, chains, proposals, rays, range);
    const float p = ctx.largeSteps->probability;
    for (size_t i = range.begin; i < range.end; ++i) {
      if (chains.stepsLeft[i] == 0 || !(uniformDouble(chains.key[i], stepDim(chains.step[i], kDimLargeStep)) < p))
        continue;
      proposals.mutation[i] = uint8_t(MutationKind::LargeStep);
      proposals.state[i] = kProposalLarge;
      proposals.reason[i] = kRejectNone;
      disableRay(rays, i);
    }
  }
};

// n with probability P(n) for u uniform in [0, 1).
int drawLength(const LargeStepModel& m, double u) {
  double sum = 0;
  for (int n = m.minVertices; n < m.maxVertices; ++n)
    if (u < (sum += m.lengthProbability[n])) return n;
  return m.maxVertices;
}

void rejectLarge(ProposalQueue& proposals, size_t slot, RejectReason why) {
  proposals.state[slot] = kProposalRejected;
  proposals.reason[slot] = why;
}

}  // namespace

const ProposalPolicy& mltChooser() {
  static const MltChooser chooser;
  return chooser;
}

InPlaceReason mltDomainReason(const StepConfig& ctx, const PathVertex* path, int n, float filmX, float filmY, float& w) {
  const LargeStepModel& m = *ctx.largeSteps;
  w = 0;
  // Shorter paths are the direct pass's (seedForChains leaves them out before this).
  if (n < m.minVertices) return kInPlaceNoMutation;
  if (n > m.maxVertices) return kInPlaceTooLong;
  const int32_t light = path[n - 1].emitter;
  if (light >= 0 && ctx.measure.scene.emitters[size_t(light)].kind == EmitterKind::Directional)
    return kInPlaceDirectionalLight;
  if (pathHasZeroContribution(ctx, path, n, filmX, filmY)) return kInPlaceZeroContribution;
  w = largeStepWeight(ctx.measure, m, path, n);
  return w > 0 ? kInPlaceReasonCount : kInPlaceOutsideLargeStep;
}

float mltDomainWeight(const StepConfig& ctx, const PathVertex* path, int n, float filmX, float filmY) {
  float w;
  mltDomainReason(ctx, path, n, filmX, filmY, w);
  return w;
}

void largeStepSample(const ChainQueue& chains, size_t slot, uint32_t pixels, uint32_t& pixel, uint32_t& sample) {
  const uint64_t key = chains.key[slot];
  const uint32_t step = chains.step[slot];
  pixel = uint32_t(uniformIndex(key, stepDim(step, kDimStart1), pixels));  // exactly 1 / pixels each (W assumes it)
  // 32 bits of the chain's key and step: two large steps that draw the same pixel share a
  // sample stream only if these collide too (about once in 4e9 pairs).
  sample = uniformUint(key, stepDim(step, kDimLargeStep + 1));
}

void largeStepTarget(const LargeStepModel& m, const ChainQueue& chains, size_t slot, int& vertices, bool& nee) {
  const uint64_t key = chains.key[slot];
  const uint32_t step = chains.step[slot];
  vertices = drawLength(m, uniformDouble(key, stepDim(step, kDimStart2)));
  nee = uniformDouble(key, stepDim(step, kDimPerturb)) < m.neeProbability(vertices);
}

void stageMltLargeSteps(const StepConfig& ctx, const ChainQueue& chains, const SeedStore& samples,
                        const uint32_t* slotOf, size_t count, ProposalQueue& proposals, VertexQueue& proposalVertices) {
  const LargeStepModel& m = *ctx.largeSteps;
  // What each chain asks of its sample, then the first seed of each sample that matches.
  std::vector<uint8_t> wantVertices(count), wantNee(count);
  std::vector<int64_t> candidate(count, -1);
  for (size_t k = 0; k < count; ++k) {
    int n;
    bool nee;
    largeStepTarget(m, chains, slotOf[k], n, nee);
    wantVertices[k] = uint8_t(n);
    wantNee[k] = nee;
  }
  const SeedQueue& seeds = samples.seeds;
  for (size_t s = 0; s < samples.size(); ++s) {
    const uint32_t k = seeds.path[s];
    if (k < count && candidate[k] < 0 && seeds.vertexCount[s] == wantVertices[k] && seeds.explicitLight[s] == wantNee[k])
      candidate[k] = int64_t(s);
  }
  PathVertex z[kMaxChainVertices];
  uint8_t kinds[kMaxChainVertices];
  for (size_t k = 0; k < count; ++k) {
    const size_t slot = slotOf[k];
    if (candidate[k] < 0) {
      rejectLarge(proposals, slot, kRejectNoCandidate);
      continue;
    }
    const size_t s = size_t(candidate[k]);
    const int n = int(seeds.vertexCount[s]);
    for (int j = 0; j < n; ++j) {
      loadPathVertex(samples.vertices, seeds.vertexBegin[s] + size_t(j), z[j]);
      kinds[j] = z[j].kind;
    }
    const float w = mltDomainWeight(ctx, z, n, seeds.filmX[s], seeds.filmY[s]);
    const Color estimate(seeds.estimateR[s], seeds.estimateG[s], seeds.estimateB[s]);
    const float lum = luminance(estimate);
    if (!(w > 0) || !(lum > 0) || !std::isfinite(lum)) {
      rejectLarge(proposals, slot, kRejectOutsideDomain);
      continue;
    }
    for (int j = 0; j < n; ++j)
      proposalVertices.copyRow(slot * kMaxChainVertices + size_t(j), samples.vertices, seeds.vertexBegin[s] + size_t(j));
    proposals.vertexCount[slot] = uint8_t(n);
    proposals.signature[slot] = packSignature(kinds, n);
    proposals.filmX[slot] = seeds.filmX[s];
    proposals.filmY[slot] = seeds.filmY[s];
    proposals.colorSet(slot, estimate / lum);
    proposals.largeWeight[slot] = w;
    proposals.state[slot] = kProposalComplete;
  }
}

}  // namespace erpt
