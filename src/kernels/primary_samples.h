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
//   s1 = s2 / 16, or by a normal offset, modulo 1 (both symmetric); a large step draws every
//   dimension afresh.
// - Dimensions past the kept slots (paths longer than the slots hold) are drawn afresh by
//   every proposal: an independence proposal, also symmetric.
// Every proposal's numbers are a pure function of the state and the attempt's stream key, so
// a dimension read twice gives the same value, and the image is the same for any thread count.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "kernels/sample_dimensions.h"

namespace erpt {

// How a small step moves a kept number: Kelemen's exponential offset (pssmlt, Mitsuba) or a
// normal one (mmlt, pbrt-v4), both symmetric, modulo 1.
enum class StepKind { Kelemen, Normal };

class PrimarySamples {
 public:
  // Kept numbers per stream: film x and y, 15 bounces of 8, mmlt's strategy and the lens
  // (camera); the emission sample, 14 bounces and the lens point of light tracing (a BDPT
  // sample's light subpath).
  static constexpr uint32_t kSlotsPerStream = 128;

  // smallStep: Kelemen's s2, the largest offset of a small step, or the normal offset's
  // standard deviation. lightSubpaths: the chains replay BDPT samples, whose light subpaths
  // draw from a stream of their own.
  PrimarySamples(size_t chains, double smallStep, bool lightSubpaths = false, StepKind kind = StepKind::Kelemen);
  size_t chains() const { return attemptKey_.size(); }

  // Chain c's next proposal draws from stream `attemptKey`: afresh everywhere (large) or from
  // its current vector by small steps. Forgets the previous proposal.
  void propose(size_t c, uint64_t attemptKey, bool large);
  // Dimension `dim` of a chain's proposal, as 64 random bits (the top ones are its value).
  // `stream`: the chain's index, with kLightSubpathStream set for its light subpath.
  uint64_t bits(uint64_t stream, uint32_t dim);
  // The proposal becomes chain c's state: the numbers it read, with their values.
  void accept(size_t c);
  // Whether chain c's state keeps dimension `dim` of `stream` (tests).
  bool keeps(uint64_t stream, uint32_t dim) const;

  // A small step's offset from 64 random bits, in units of 2^-64 (added modulo 2^64).
  uint64_t smallStepOffset(uint64_t random) const;

 private:
  // The chain's slot of a stream's dimension, or slots_ when it is not kept.
  uint32_t slotOf(uint64_t stream, uint32_t dim) const;
  size_t chainOf(uint64_t stream) const { return size_t(stream & ~kLightSubpathStream); }
  bool has(const std::vector<uint64_t>& mask, size_t c, uint32_t slot) const {
    return (mask[c * maskWords_ + slot / 64] >> (slot % 64)) & 1;
  }

  StepKind kind_;
  double smallStep_, logRatio_;
  uint32_t slots_, maskWords_;                        // per chain
  std::vector<uint64_t> current_, proposed_;          // chain c's slot s at c * slots_ + s
  std::vector<uint64_t> currentMask_, proposedMask_;  // maskWords_ per chain
  std::vector<uint64_t> attemptKey_;
  std::vector<uint64_t> lightKey_;  // the attempt's light-subpath stream, hashed once per proposal
  std::vector<uint8_t> large_;
};

}  // namespace erpt
