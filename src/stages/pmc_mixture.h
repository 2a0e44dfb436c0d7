// PMC-ER's kernel (paper eq. 5, 8, 9): a mixture over perturbation radii d_k with weights
// alpha_k; a proposal picks k by alpha, then the caustic perturbation (theta uniform in
// [0, theta_max(d_k)], eq. 6) with probability gamma_caustic where it applies, else the lens
// perturbation (film position uniform in the disk of radius d_k). The acceptance uses the
// chosen component's T ratio (eq. 9); that is valid when the choice has the same probability
// at y and at z, or when the ratio of those probabilities enters the acceptance:
//   Member and Off: alpha is the member's and fixed during an iteration (ratio 1);
//   Region: alpha is a table over image regions, so a(y) = alpha_k(region of y) and
//     a(z) = alpha_k(region of z) differ; selectionRatios() gives a(z) / a(y).
// gamma depends on the path's signature only, which the perturbations keep (ratio 1).
#pragma once

#include <vector>

#include "core/byte_stream.h"
#include "stages/chain_stages.h"
#include "erpt/pmc_settings.h"

namespace erpt {

// alpha_k = eps + (1 - K eps) s_k / sum(s) from acceptance sums s (uniform when the sum is
// 0): the paper's rule, with the floor eps kept and the weights summing to 1 (the paper's
// eps + (1 - eps) s_k / sum(s) sums to 1 + (K - 1) eps).
void alphaFromAcceptance(const double* sums, int components, float eps, float* alpha);
// The component u in [0, 1) picks from alpha.
int pickComponent(const float* alpha, int components, float u);

class PmcMixture final : public ProposalPolicy {
 public:
  PmcMixture(const PmcSettings& settings, int width, int height);
  int components() const { return int(radii_.size()); }
  const std::vector<float>& radii() const { return radii_; }
  PmcAdapt adapt() const { return adapt_; }

  // Member mode: the members' weights, `components()` per chain slot (owned by the caller).
  void setMemberWeights(const float* alpha) { memberAlpha_ = alpha; }
  // Region mode: the region a film position belongs to (positions off the image are clamped
  // to the border regions; any fixed function of the position would do), and the table.
  int regionOf(float filmX, float filmY) const;
  int regionCount() const { return regionsX_ * regionsY_; }
  // Builds the table from acceptance sums per region and component (regions x K), each with a
  // prior of `prior` acceptances per component (regions that saw few proposals stay near
  // uniform).
  void setRegionTable(const std::vector<double>& sums, double prior);
  const std::vector<float>& regionTable() const { return table_; }
  // Render state (a checkpoint holds the table the training population built).
  void save(ByteWriter& w) const { w.putVector(table_); }
  void load(ByteReader& r) { r.getVector(table_, table_.size()); }
  // The weights the proposal of `slot` at film position (x, y) uses.
  const float* weightsFor(size_t slot, float filmX, float filmY) const;

  void choose(const StepConfig& ctx, const ChainQueue& chains, ProposalQueue& proposals, RayQueue& rays,
              IndexRange range) const override;
  void selectionRatios(const ChainQueue& chains, ProposalQueue& proposals, IndexRange range) const override;

 private:
  std::vector<float> radii_;
  PmcAdapt adapt_;
  float eps_, causticProb_;
  int regionSize_, regionsX_, regionsY_;
  std::vector<float> uniform_, table_;
  const float* memberAlpha_ = nullptr;
};

}  // namespace erpt
