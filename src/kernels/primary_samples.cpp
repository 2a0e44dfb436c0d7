#include "kernels/primary_samples.h"

#include <cmath>

#include "core/rng.h"
#include "kernels/normal_ziggurat.h"
#include "kernels/sample_dimensions.h"

namespace erpt {

namespace {
// Kelemen's s1 = s2 / 16 (1/1024 and 1/64 in the paper and in Mitsuba 0.6).
constexpr double kSmallStepRatio = 16;
}  // namespace

PrimarySamples::PrimarySamples(size_t chains, double smallStep, bool lightSubpaths, StepKind kind)
    : kind_(kind),
      smallStep_(smallStep),
      logRatio_(std::log(kSmallStepRatio)),
      slots_(kSlotsPerStream * (lightSubpaths ? 2 : 1)),
      maskWords_(slots_ / 64),
      current_(chains * slots_),
      proposed_(chains * slots_),
      currentMask_(chains * maskWords_),
      proposedMask_(chains * maskWords_),
      attemptKey_(chains),
      lightKey_(chains),
      large_(chains) {}

uint32_t PrimarySamples::slotOf(uint64_t stream, uint32_t dim) const {
  const bool light = (stream & kLightSubpathStream) != 0;
  if (light && slots_ == kSlotsPerStream) return slots_;
  const uint32_t base = light ? kSlotsPerStream : 0;
  if (dim == kDimLensX || dim == kDimLensY) return base + kSlotsPerStream - 2 + (dim - kDimLensX);
  if (dim == kDimBdptStrategy) return light ? slots_ : kSlotsPerStream - 3;
  // The light subpath's emission sample takes its first slots, its bounces the next ones (its
  // dimensions 0 and 1, the camera's film position, are never read).
  if (light && dim >= kDimEmitPick && dim < kDimEmitPick + kEmitDims) return base + (dim - kDimEmitPick);
  const uint32_t local = light ? dim + kEmitDims : dim;
  return local < kSlotsPerStream - 3 ? base + local : slots_;
}

void PrimarySamples::propose(size_t c, uint64_t attemptKey, bool large) {
  attemptKey_[c] = attemptKey;
  lightKey_[c] = mix64(attemptKey ^ kLightSubpathStream);
  large_[c] = large;
  for (uint32_t w = 0; w < maskWords_; ++w) proposedMask_[c * maskWords_ + w] = 0;
}

uint64_t PrimarySamples::smallStepOffset(uint64_t random) const {
  if (kind_ == StepKind::Normal) {
    // sigma z, z standard normal (kernels/normal_ziggurat.h), taken modulo 1.
    const double offset = smallStep_ * standardNormalFromBits(random);
    const double fraction = offset - std::floor(offset);  // in [0, 1]
    return fraction >= 1 ? 0 : uint64_t(fraction * 0x1p64);
  }
  // |offset| = s2 (s1 / s2)^u, u uniform in [0, 1) from 52 bits; the top bit is the sign.
  const double u = double((random >> 11) & ((uint64_t(1) << 52) - 1)) * 0x1p-52;
  const double offset = smallStep_ * std::exp(-logRatio_ * u);
  const uint64_t units = uint64_t(offset * 0x1p64);  // offset <= s2 <= 1/2: no overflow
  return (random >> 63) ? 0 - units : units;
}

uint64_t PrimarySamples::bits(uint64_t stream, uint32_t dim) {
  const size_t c = chainOf(stream);
  // The light subpath's numbers come from another stream of the attempt than the camera's.
  const uint64_t key = (stream & kLightSubpathStream) ? lightKey_[c] : attemptKey_[c];
  const uint32_t slot = slotOf(stream, dim);
  if (slot >= slots_) return uniformBits(key, dim);
  const size_t at = c * slots_ + slot;
  uint64_t& word = proposedMask_[c * maskWords_ + slot / 64];
  const uint64_t bit = uint64_t(1) << (slot % 64);
  if (word & bit) return proposed_[at];
  // A small step moves a kept value; the rest are drawn afresh (see the header). The offset's
  // random bits come from another dimension of the attempt's stream than the fresh value's.
  const bool kept = !large_[c] && has(currentMask_, c, slot);
  const uint64_t value =
      kept ? current_[at] + smallStepOffset(uniformBits(key, dim ^ 0x80000000u)) : uniformBits(key, dim);
  proposed_[at] = value;
  word |= bit;
  return value;
}

void PrimarySamples::accept(size_t c) {
  for (uint32_t w = 0; w < maskWords_; ++w) {
    uint64_t mask = proposedMask_[c * maskWords_ + w];
    currentMask_[c * maskWords_ + w] = mask;
    while (mask) {
      const uint32_t slot = w * 64 + uint32_t(__builtin_ctzll(mask));
      current_[c * slots_ + slot] = proposed_[c * slots_ + slot];
      mask &= mask - 1;
    }
  }
}

bool PrimarySamples::keeps(uint64_t stream, uint32_t dim) const {
  const uint32_t slot = slotOf(stream, dim);
  return slot < slots_ && has(currentMask_, chainOf(stream), slot);
}

}  // namespace erpt
