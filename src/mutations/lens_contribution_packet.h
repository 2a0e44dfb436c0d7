// The lens perturbation's f(z) (lensContribution) for a run of chain slots at once, in vector
// lanes, for the proposals of its commonest shape: vertex 1 regenerated on an untextured
// diffuse surface and connected to the fixed vertex 2, itself untextured diffuse (then vertex
// 3 follows) or an area light, with the chain's fixed tail and lum(f(y)) cached in the lens
// measure. For those, the scalar unit loads the current path's first vertices and the
// proposal's, and evaluates the path through two general BSDF calls, each a chain of
// dependent divisions and square roots; here eight proposals share each instruction. The
// accept stage takes f(z) from the packet for the slots it took and asks the unit for the
// rest: the same f, rounding aside.
#pragma once

#include <cstddef>
#include <cstdint>

#include "mutations/mutation.h"

namespace erpt {

class LensContributionPacket {
 public:
  static constexpr size_t kCapacity = 64;

  // Takes the slots of [begin, begin + count) (count <= kCapacity) whose complete proposal
  // has that shape and evaluates their f(z). Reads the slots' rows only.
  void evaluate(const StepConfig& ctx, const ChainQueue& chains, const VertexQueue& chainVertices,
                const ProposalQueue& proposals, const VertexQueue& proposalVertices, size_t begin, size_t count);
  // Whether slot i (in the evaluated run) was taken, and its f(z).
  bool took(size_t i) const { return row_[i - begin_] >= 0; }
  Color fz(size_t i) const {
    const size_t j = size_t(row_[i - begin_]);
    return Color(out_[kFr][j], out_[kFg][j], out_[kFb][j]);
  }

 private:
  bool qualifies(const StepConfig& ctx, const ChainQueue& chains, const VertexQueue& chainVertices,
                 const ProposalQueue& proposals, const VertexQueue& proposalVertices, size_t i);
  // Inputs add() reads once per slot (the materials' colours, the light's radiance, the film
  // density); the vertices and the tail are gathered in the lanes by slot.
  enum Input { kDensity, kR1, kG1, kB1, kTwoSided1, kR2, kG2, kB2, kTwoSided2, kLight2, kInputs };
  enum Output { kFr, kFg, kFb, kOutputs };
  size_t begin_ = 0, count_ = 0;
  int32_t row_[kCapacity];                        // slot begin_ + r's packet row, -1 when not taken
  alignas(64) int32_t slot_[kCapacity] = {};      // the chain slot of each packet row
  alignas(64) int32_t vertexRow_[kCapacity] = {};  // its first vertex row (slot * kMaxChainVertices)
  alignas(64) float in_[kInputs][kCapacity] = {};
  alignas(64) float out_[kOutputs][kCapacity] = {};
};

}  // namespace erpt
