#include "kernels/primary_samples.h"

#include <cmath>

#include "core/rng.h"
#include "kernels/sample_dimensions.h"

namespace erpt {

namespace {
// Kelemen's s1 = s2 / 16 (1/1024 and 1/64 in the paper and in Mitsuba 0.6).
constexpr double kSmallStepRatio = 16;
}  // namespace

PrimarySamples::PrimarySamples(size_t chains, double smallStep)
    : smallStep_(smallStep),
      logRatio_(std::log(kSmallStepRatio)),
      current_(chains * kKeptSlots),
      proposed_(chains * kKeptSlots),
      currentMask_(chains * kMaskWords),
      proposedMask_(chains * kMaskWords),
      attemptKey_(chains),
      large_(chains) {}

uint32_t PrimarySamples::slotOf(uint32_t dim) {
  if (dim == kDimLensX || dim == kDimLensY) return kKeptSlots - 2 + (dim - kDimLensX);
  return dim < kKeptSlots - 2 ? dim : kKeptSlots;
}

void PrimarySamples::propose(size_t c, uint64_t attemptKey, bool large) {
  attemptKey_[c] = attemptKey;
  large_[c] = large;
  for (uint32_t w = 0; w < kMaskWords; ++w) proposedMask_[c * kMaskWords + w] = 0;
}

uint64_t PrimarySamples::smallStepOffset(uint64_t random) const {
  // |offset| = s2 (s1 / s2)^u, u uniform in [0, 1) from 52 bits; the top bit is the sign.
  const double u = double((random >> 11) & ((uint64_t(1) << 52) - 1)) * 0x1p-52;
  const double offset = smallStep_ * std::exp(-logRatio_ * u);
  const uint64_t units = uint64_t(offset * 0x1p64);  // offset <= s2 <= 1/2: no overflow
  return (random >> 63) ? 0 - units : units;
}

uint64_t PrimarySamples::bits(size_t c, uint32_t dim) {
  const uint64_t fresh = uniformBits(attemptKey_[c], dim);
  const uint32_t slot = slotOf(dim);
  if (slot >= kKeptSlots) return fresh;
  const size_t at = c * kKeptSlots + slot;
  uint64_t& word = proposedMask_[c * kMaskWords + slot / 64];
  const uint64_t bit = uint64_t(1) << (slot % 64);
  if (word & bit) return proposed_[at];
  // A small step moves a kept value; the rest are drawn afresh (see the header). The offset's
  // random bits come from another dimension of the attempt's stream than the fresh value's.
  const bool kept = !large_[c] && has(currentMask_, c, slot);
  const uint64_t value = kept ? current_[at] + smallStepOffset(uniformBits(attemptKey_[c], dim ^ 0x80000000u)) : fresh;
  proposed_[at] = value;
  word |= bit;
  return value;
}

void PrimarySamples::accept(size_t c) {
  for (uint32_t w = 0; w < kMaskWords; ++w) {
    uint64_t mask = proposedMask_[c * kMaskWords + w];
    currentMask_[c * kMaskWords + w] = mask;
    while (mask) {
      const uint32_t slot = w * 64 + uint32_t(__builtin_ctzll(mask));
      current_[c * kKeptSlots + slot] = proposed_[c * kKeptSlots + slot];
      mask &= mask - 1;
    }
  }
}

bool PrimarySamples::keeps(size_t c, uint32_t dim) const {
  const uint32_t slot = slotOf(dim);
  return slot < kKeptSlots && has(currentMask_, c, slot);
}

}  // namespace erpt
