// Primary sample space (Kelemen, Szirmay-Kalos, Antal and Csonka 2002): a path is the image of
// a vector of uniform numbers under a sampler (the path tracer), and a Markov chain moves the
// vector instead of the path. PrimarySamples holds the vectors of many chains and is the
// sampler's source of numbers while their proposals are traced (StageContext::replay): the
// stages ask for dimension d of stream `key` and, replaying, key is the chain's index.
//
// State and proposal, exactly (docs/pssmlt.md derives them):
// - A chain keeps the dimensions its current path read (a mask), as 64-bit fixed-point values
//   in [0, 1). The path does not depend on the others, so their conditional under the target
//   is uniform: they are drawn afresh whenever a proposal reads them (a Gibbs step, always
//   valid).
// - A small step moves every kept dimension by Kelemen's exponential offset, +-s2 (s1/s2)^u,
//   s1 = s2 / 16, modulo 1 (symmetric); a large step draws every dimension afresh.
// - Dimensions past kKeptSlots (paths longer than the slots hold) are drawn afresh by every
//   proposal: an independence proposal, also symmetric.
// Every proposal's numbers are a pure function of the state and the attempt's stream key, so
// a dimension read twice gives the same value, and the image is the same for any thread count.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace erpt {

class PrimarySamples {
 public:
  // Kept dimensions per chain: film x and y, 15 bounces of the path tracer's 8 and the lens.
  static constexpr uint32_t kKeptSlots = 128;

  // smallStep: Kelemen's s2, the largest offset of a small step.
  PrimarySamples(size_t chains, double smallStep);
  size_t chains() const { return attemptKey_.size(); }

  // Chain c's next proposal draws from stream `attemptKey`: afresh everywhere (large) or from
  // its current vector by small steps. Forgets the previous proposal.
  void propose(size_t c, uint64_t attemptKey, bool large);
  // Dimension `dim` of chain c's proposal, as 64 random bits (the top ones are its value).
  uint64_t bits(size_t c, uint32_t dim);
  // The proposal becomes chain c's state: the dimensions it read, with their values.
  void accept(size_t c);
  // Dimensions chain c's state keeps (tests).
  bool keeps(size_t c, uint32_t dim) const;

  // Kelemen's offset from 64 random bits, in units of 2^-64 (added modulo 2^64).
  uint64_t smallStepOffset(uint64_t random) const;

 private:
  static constexpr uint32_t kMaskWords = kKeptSlots / 64;
  // The slot of a sampler dimension, or kKeptSlots when it is not kept.
  static uint32_t slotOf(uint32_t dim);
  bool has(const std::vector<uint64_t>& mask, size_t c, uint32_t slot) const {
    return (mask[c * kMaskWords + slot / 64] >> (slot % 64)) & 1;
  }

  double smallStep_, logRatio_;
  std::vector<uint64_t> current_, proposed_;          // chain c's slot s at c * kKeptSlots + s
  std::vector<uint64_t> currentMask_, proposedMask_;  // kMaskWords per chain
  std::vector<uint64_t> attemptKey_;
  std::vector<uint8_t> large_;
};

}  // namespace erpt
