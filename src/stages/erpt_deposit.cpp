// ERPT deposit stage: the step's deposit records go to the film one slot after another, so
// the sums (and the image) do not depend on how the other stages were split over threads.
// The noise filters of the paper's section 4.4 run here, over the same records: the
// consecutive-sample filter drops records, the proposed-mutations filter counts proposals.
#include <cmath>

#include "erpt/erpt_stages.h"

namespace erpt {

namespace {

// The pixel a film position falls in, packed as two 16-bit coordinates (positions a little
// outside the image, where wide filters still sample, get their own codes).
uint32_t pixelCode(float x, float y) {
  const auto c = [](float v) { return uint32_t(uint16_t(int16_t(std::floor(v)))); };
  return c(x) | (c(y) << 16);
}

}  // namespace

void clearStepDeposits(DepositQueue& deposits, size_t i) {
  for (size_t k = 0; k < kDepositsPerStep; ++k) deposits.setRow(i * kDepositsPerStep + k, DepositQueue::Row{});
}

void writeStepDeposits(const ErptSettings& s, const StepDeposit& before, const StepDeposit& proposal, float q,
                       bool moved, float energy, DepositQueue& deposits, size_t i) {
  const size_t row = i * kDepositsPerStep;
  // Detailed balance (section 3.1): the mutation receives e q / m, the rest stays at x.
  if (s.expectedDeposit || s.flow == FlowRule::DetailedBalance) {
    deposits.setRow(row, {before.filmX, before.filmY, before.color * (energy * (1 - q))});
    if (q > 0) deposits.setRow(row + 1, {proposal.filmX, proposal.filmY, proposal.color * (energy * q)});
    return;
  }
  const StepDeposit& at = moved ? proposal : before;
  deposits.setRow(row, {at.filmX, at.filmY, at.color * energy});
}

double applyDeposits(ChainQueue& chains, const ProposalQueue& proposals, const DepositQueue& deposits, IndexRange range,
                     const FilmDensity& density, Film& film, DepositFilters& filters) {
  double total = 0;
  auto splat = [&](float x, float y, Color c, bool discard) {
    if (isBlack(c)) return;
    if (discard) {
      ++filters.discarded;
      filters.discardedEnergy += luminance(c);
      return;
    }
    total += luminance(c);
    density.splat(x, y, [&](uint32_t pixel, float w) { film.add(pixel, c * w); });
  };
  const int w = density.width(), h = density.height();
  for (size_t i = range.begin; i < range.end; ++i) {
    // Only slots that took a step this round have records; a free slot's are zero.
    uint32_t stuckPixel = kNoPixel;
    if (filters.maxConsecutive > 0 && chains.step[i] > 0) {
      // The chain's path after this step: the same pixel as the step before extends the run.
      const uint32_t p = pixelCode(chains.filmX[i], chains.filmY[i]);
      chains.runLength[i] = p == chains.runPixel[i] ? chains.runLength[i] + 1 : 1;
      chains.runPixel[i] = p;
      if (chains.runLength[i] > filters.maxConsecutive) stuckPixel = p;
    }
    for (size_t k = 0; k < kDepositsPerStep; ++k) {
      const DepositQueue::Row d = deposits.row(i * kDepositsPerStep + k);
      splat(d.x, d.y, d.energy, pixelCode(d.x, d.y) == stuckPixel);
    }
    // A proposal goes "to" the pixel of its film position as soon as it has one: a lens
    // proposal from the start (valid or not), a caustic one once it reached the eye.
    if (filters.proposalTally &&
        (proposals.state[i] == kProposalComplete || proposals.mutation[i] == uint8_t(MutationKind::Lens))) {
      const float px = std::floor(proposals.filmX[i]), py = std::floor(proposals.filmY[i]);
      if (px >= 0 && py >= 0 && px < float(w) && py < float(h)) ++(*filters.proposalTally)[size_t(py) * size_t(w) + size_t(px)];
    }
  }
  return total;
}

}  // namespace erpt
