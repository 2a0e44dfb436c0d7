// PMC-ER's mixture kernel as the mutate stage's chooser (pmc_mixture.h).
#include "stages/pmc_mixture.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/rng.h"

namespace erpt {

void alphaFromAcceptance(const double* sums, int k, float eps, float* alpha) {
  double total = 0;
  for (int i = 0; i < k; ++i) total += std::max(0.0, sums[i]);
  for (int i = 0; i < k; ++i)
    alpha[i] = total > 0 ? float(double(eps) + (1.0 - double(k) * eps) * std::max(0.0, sums[i]) / total) : 1.0f / float(k);
}

int pickComponent(const float* alpha, int k, float u) {
  float c = 0;
  for (int i = 0; i + 1 < k; ++i) {
    c += alpha[i];
    if (u < c) return i;
  }
  return k - 1;
}

PmcMixture::PmcMixture(const PmcSettings& s, int width, int height)
    : radii_(s.radii), adapt_(s.adapt), eps_(s.alphaFloor), causticProb_(s.causticProb), regionSize_(std::max(1, s.regionSize)) {
  if (radii_.empty() || radii_.size() > size_t(kMaxPmcRadii)) throw std::invalid_argument("PmcMixture: 1 to 8 radii");
  regionsX_ = (width + regionSize_ - 1) / regionSize_;
  regionsY_ = (height + regionSize_ - 1) / regionSize_;
  uniform_.assign(radii_.size(), 1.0f / float(radii_.size()));
  table_.clear();
  for (int r = 0; r < regionCount(); ++r) table_.insert(table_.end(), uniform_.begin(), uniform_.end());
}

int PmcMixture::regionOf(float x, float y) const {
  const int rx = std::clamp(int(std::floor(x / float(regionSize_))), 0, regionsX_ - 1);
  const int ry = std::clamp(int(std::floor(y / float(regionSize_))), 0, regionsY_ - 1);
  return ry * regionsX_ + rx;
}

void PmcMixture::setRegionTable(const std::vector<double>& sums, double prior) {
  const int k = components();
  std::vector<double> s(static_cast<size_t>(k), 0.0);
  for (int r = 0; r < regionCount(); ++r) {
    for (int i = 0; i < k; ++i) s[size_t(i)] = sums[size_t(r * k + i)] + prior;
    alphaFromAcceptance(s.data(), k, eps_, &table_[size_t(r * k)]);
  }
}

const float* PmcMixture::weightsFor(size_t slot, float x, float y) const {
  switch (adapt_) {
    case PmcAdapt::Member: return memberAlpha_ ? memberAlpha_ + slot * radii_.size() : uniform_.data();
    case PmcAdapt::Region: return &table_[size_t(regionOf(x, y)) * radii_.size()];
    case PmcAdapt::Off: break;
  }
  return uniform_.data();
}

void PmcMixture::choose(const StepConfig& ctx, const ChainQueue& chains, ProposalQueue& proposals, RayQueue& rays,
                        IndexRange range) const {
  uint8_t kinds[kMaxChainVertices];
  const int k = components();
  for (size_t i = range.begin; i < range.end; ++i) {
    if (chains.stepsLeft[i] == 0) continue;
    const int n = chains.vertexCount[i];
    unpackSignature(chains.signature[i], n, kinds);
    // The families the path's form allows (the Mixed strategy's), then gamma between them.
    const bool lens = chooseMutation(MutationStrategy::LensOnly, kinds, n, 0) != MutationKind::None;
    const bool caustic = chooseMutation(MutationStrategy::CausticOnly, kinds, n, 0) != MutationKind::None;
    if (!lens) {
      rejectProposal(proposals, rays, i, kRejectNoMutation);
      continue;
    }
    const uint64_t key = chains.key[i];
    const uint32_t step = chains.step[i];
    const bool useCaustic = caustic && uniformFloat(key, stepDim(step, kDimStrategy)) < causticProb_;
    const int c = pickComponent(weightsFor(i, chains.filmX[i], chains.filmY[i]), k,
                                uniformFloat(key, stepDim(step, kDimComponent)));
    // The manifold coin, after gamma's, so that the component's draw stays where it was.
    proposals.mutation[i] = uint8_t(choosesManifold(ctx, chains, i, kinds, n) ? MutationKind::Manifold
                                    : useCaustic                              ? ctx.causticKind()
                                                                              : ctx.lensKind());
    proposals.perturbSize[i] = radii_[size_t(c)];
    proposals.component[i] = uint8_t(c);
    proposals.state[i] = kProposalWalking;
  }
}

void PmcMixture::selectionRatios(const ChainQueue& chains, ProposalQueue& proposals, IndexRange range) const {
  if (adapt_ != PmcAdapt::Region) return;
  const size_t k = radii_.size();
  for (size_t i = range.begin; i < range.end; ++i) {
    if (proposals.state[i] != kProposalComplete) continue;
    const size_t c = proposals.component[i];
    const float ay = table_[size_t(regionOf(chains.filmX[i], chains.filmY[i])) * k + c];
    const float az = table_[size_t(regionOf(proposals.filmX[i], proposals.filmY[i])) * k + c];
    proposals.selection[i] = az / ay;
  }
}

}  // namespace erpt
