// What every stage of a chain step and every mutation unit reads: the scene's measure context,
// the step's settings, and the random dimensions of a step.
#pragma once

#include <cstdint>

#include "erpt/erpt_settings.h"
#include "kernels/erpt_path.h"

namespace erpt {

struct LargeStepModel;

struct VertexRange {
  int min = 2, max = kMaxChainVertices;
};

// The user's options that the stages and units read (defaults: ChainOptions' and
// ErptSettings', declared there).
struct StepSettings {
  MutationStrategy strategy = ChainOptions{}.strategy;
  float lensRadius = ChainOptions{}.lensRadius;
  LensShape lensShape = ChainOptions{}.lensShape;
  CausticAngle causticAngle = ChainOptions{}.causticAngle;
  FlowRule flow = ErptSettings{}.flow;  // DetailedBalance (ERPT's): chains never move
  bool expectedDeposit = ChainOptions{}.expectedDeposit;
  float bidirectional = ChainOptions{}.bidirectionalMutation;  // P(bidirectional mutation) per step
  float manifold = ChainOptions{}.manifoldPerturbation;  // P(manifold perturbation) per step where it applies
};
inline StepSettings stepSettingsOf(const ChainOptions& s, FlowRule flow = FlowRule::EqualDeposition) {
  return StepSettings{s.strategy, s.lensRadius, s.lensShape, s.causticAngle, flow, s.expectedDeposit,
                      s.bidirectionalMutation, s.manifoldPerturbation};
}

struct StepConfig {
  MeasureContext measure;
  StepSettings settings;
  // MLT: the large step's model, which the accept stage needs for W(y) (null: no large steps).
  const LargeStepModel* largeSteps = nullptr;
  // The path lengths the chains hold (vertices, eye and light included; the direct pass takes
  // the shorter ones): the bidirectional mutation proposes no others.
  VertexRange lengths = VertexRange{};
  // The mutation units the settings' lens shape and caustic angle choose for the two families.
  MutationKind lensKind() const { return settings.lensShape == LensShape::Disk ? MutationKind::LensDisk : MutationKind::Lens; }
  MutationKind causticKind() const {
    return settings.causticAngle == CausticAngle::Veach ? MutationKind::CausticVeach : MutationKind::Caustic;
  }
};

// Random dimensions of one chain step (stream key = the chain's key, dimension =
// step * kStepDims + use). Direction perturbations at vertex j use kDimPerturb + 2j, +1.
// kDimComponent: the mixture component (PMC-ER's radius), after the last perturbation's.
// kDimBidirectional: the coin for the bidirectional mutation, whose own numbers come from a
// stream of their own (chain_bidirectional.cpp). kDimLargeStep: MLT's coin for a large step; a large step then draws its pixel, path length
// and technique from kDimStart1, kDimStart2 and kDimPerturb (no perturbation uses them then).
// kDimManifold: the coin for the manifold perturbation.
enum StepDim : uint32_t {
  kDimStrategy = 0, kDimAccept, kDimStart1, kDimStart2, kDimPerturb, kDimLargeStep = 46, kDimManifold = 47, kDimComponent = 48,
  kDimBidirectional = 49,
  kStepDims = 50
};
static_assert(kDimPerturb + 2 * kMaxChainVertices <= kDimLargeStep, "step dimensions overlap");
// The most steps a chain may take before its dimensions would wrap around 32 bits (and repeat
// its first steps' numbers); the chain drivers keep every chain below it.
constexpr uint32_t kMaxChainSteps = UINT32_MAX / kStepDims;
inline uint32_t stepDim(uint32_t step, uint32_t use) { return step * kStepDims + use; }

}  // namespace erpt
