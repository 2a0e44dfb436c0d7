// Deposit stage: the step's deposit records go to the film, either one slot after
// another (a Film) or from many chain lanes at once into an ExactFilm, whose integer sums do
// not depend on the order; either way the image does not depend on the thread count.
// The noise filters of the paper's section 4.4 run here, over the same records: the
// consecutive-sample filter drops records, the proposed-mutations filter counts proposals.
#include <algorithm>
#include <cmath>
#include <tuple>

#include "stages/chain_stages.h"

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

void writeStepDeposits(const StepSettings& s, const StepDeposit& before, const StepDeposit& proposal, float q,
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

namespace {

// The film a record goes to, one kind per overload of applyDeposits.
struct SlotOrderFilm {
  Film& film;
  void prefetch(uint32_t pixel) const { film.prefetch(pixel); }
  void splat(const FilmDensity& density, const ChainQueue&, size_t, size_t, float x, float y, Color c) {
    density.splat(x, y, [&](uint32_t pixel, float w) { film.add(pixel, c * w); });
  }
};
struct LaneFilm {
  ConcurrentDeposits& target;
  void prefetch(uint32_t pixel) const { target.film.prefetch(pixel); }
  void splat(const FilmDensity& density, const ChainQueue& chains, size_t slot, size_t record, float x, float y,
             Color c) {
    if (target.film.fits(c)) {
      density.splat(x, y, [&](uint32_t pixel, float w) { target.film.add(pixel, c, w); });
      return;
    }
    target.large.push_back(LargeDeposit{chains.key[slot], chains.step[slot], uint32_t(record), x, y, c});
  }
};

// How many slots ahead the film's pixel under a slot's first record is prefetched: far enough
// for a miss to arrive while the slots between are deposited.
constexpr size_t kPrefetchAhead = 8;

template <class Target>
void prefetchPixel(const DepositQueue& deposits, size_t slot, int w, int h, Target& target) {
  const size_t row = slot * kDepositsPerStep;
  const float x = deposits.x[row], y = deposits.y[row];
  // (The records of free slots and rejected steps are zero: a prefetch of pixel 0 is harmless.)
  if (x >= 0 && y >= 0 && x < float(w) && y < float(h)) target.prefetch(uint32_t(y) * uint32_t(w) + uint32_t(x));
}

template <class Target>
double depositRecords(ChainQueue& chains, const ProposalQueue& proposals, const DepositQueue& deposits, IndexRange range,
                      const FilmDensity& density, Target target, DepositFilters& filters) {
  double total = 0;
  const int w = density.width(), h = density.height();
  for (size_t i = range.begin; i < range.end; ++i) {
    if (i + kPrefetchAhead < range.end) prefetchPixel(deposits, i + kPrefetchAhead, w, h, target);
    // Only slots that took a step this round have records; a free slot's are zero.
    bool stuck = false;
    uint32_t stuckPixel = 0;
    if (filters.maxConsecutive > 0 && chains.step[i] > 0) {
      // The chain's path after this step: the same pixel as the step before extends the run.
      const uint32_t p = pixelCode(chains.filmX[i], chains.filmY[i]);
      chains.runLength[i] = p == chains.runPixel[i] ? chains.runLength[i] + 1 : 1;
      chains.runPixel[i] = p;
      stuck = chains.runLength[i] > filters.maxConsecutive;
      stuckPixel = p;
    }
    for (size_t k = 0; k < kDepositsPerStep; ++k) {
      const DepositQueue::Row d = deposits.row(i * kDepositsPerStep + k);
      if (isBlack(d.energy)) continue;
      // (A flag, not a reserved code: a film position in (-1, 0) x (-1, 0), inside a tent or
      // gaussian filter's footprint, has the code a "no pixel" marker would have.)
      if (stuck && pixelCode(d.x, d.y) == stuckPixel) {
        ++filters.discarded;
        filters.discardedEnergy += luminance(d.energy);
        continue;
      }
      total += luminance(d.energy);
      target.splat(density, chains, i, k, d.x, d.y, d.energy);
    }
    // A proposal goes "to" the pixel of its film position as soon as it has one: a lens
    // proposal from the start (valid or not), a caustic one once it reached the eye.
    if (filters.proposalTally &&
        (proposals.state[i] == kProposalComplete || proposals.mutation[i] == uint8_t(MutationKind::Lens))) {
      const float px = std::floor(proposals.filmX[i]), py = std::floor(proposals.filmY[i]);
      if (px >= 0 && py >= 0 && px < float(w) && py < float(h)) {
        const size_t pixel = size_t(py) * size_t(w) + size_t(px);
        __atomic_fetch_add(&(*filters.proposalTally)[pixel], 1u, __ATOMIC_RELAXED);
        if (filters.acceptanceTally)
          __atomic_fetch_add(&(*filters.acceptanceTally)[pixel],
                             uint64_t(std::lround(double(proposals.acceptance[i]) / kAcceptanceUnit)), __ATOMIC_RELAXED);
      }
    }
  }
  return total;
}

}  // namespace

double applyDeposits(ChainQueue& chains, const ProposalQueue& proposals, const DepositQueue& deposits, IndexRange range,
                     const FilmDensity& density, Film& film, DepositFilters& filters) {
  return depositRecords(chains, proposals, deposits, range, density, SlotOrderFilm{film}, filters);
}

double applyDeposits(ChainQueue& chains, const ProposalQueue& proposals, const DepositQueue& deposits, IndexRange range,
                     const FilmDensity& density, ConcurrentDeposits& target, DepositFilters& filters) {
  return depositRecords(chains, proposals, deposits, range, density, LaneFilm{target}, filters);
}

void addLargeDeposits(std::vector<LargeDeposit>& large, const FilmDensity& density, Film& film) {
  std::sort(large.begin(), large.end(), [](const LargeDeposit& a, const LargeDeposit& b) {
    return std::tie(a.key, a.step, a.record) < std::tie(b.key, b.step, b.record);
  });
  for (const LargeDeposit& d : large)
    density.splat(d.x, d.y, [&](uint32_t pixel, float w) { film.add(pixel, d.energy * w); });
  large.clear();
}

}  // namespace erpt
