// The one place the mutation units are looked up by kind (the perturbations and MLT's large
// step), and the strategies' choice of a perturbation family for a path.
#include <stdexcept>

#include "mutations/mutation.h"

namespace erpt {

extern const Mutation kLensSquareMutation, kLensDiskMutation, kCausticMutation, kCausticVeachMutation, kLargeStepMutation,
    kBidirectionalMutation, kManifoldMutation;

namespace {
// Constant-initialized (addresses only), so a lookup is one indexed load.
const Mutation* const kUnits[kMutationKindCount] = {nullptr, &kLensSquareMutation, &kLensDiskMutation, &kCausticMutation,
                                                    &kCausticVeachMutation, &kLargeStepMutation,
                                                    &kBidirectionalMutation, &kManifoldMutation};
}  // namespace

const Mutation& mutationOf(MutationKind kind) {
  const Mutation* m = size_t(kind) < size_t(kMutationKindCount) ? kUnits[size_t(kind)] : nullptr;
  if (!m) throw std::logic_error("mutationOf: no mutation unit for this kind");
  return *m;
}

MutationKind chooseMutation(MutationStrategy s, const uint8_t* kinds, int n, float u) {
  if (n < 2 || n > kMaxChainVertices) return MutationKind::None;
  // The units' own suitability (both caustic units apply to the same paths).
  if (!mutationOf(MutationKind::Lens).applies(kinds, n)) return MutationKind::None;
  const bool caustic = mutationOf(MutationKind::Caustic).applies(kinds, n);
  switch (s) {
    case MutationStrategy::Paper: return isCausticPath(kinds, n) ? MutationKind::Caustic : MutationKind::Lens;
    case MutationStrategy::Mixed: return caustic && u < 0.5f ? MutationKind::Caustic : MutationKind::Lens;
    case MutationStrategy::LensOnly: return MutationKind::Lens;
    case MutationStrategy::CausticOnly: return caustic ? MutationKind::Caustic : MutationKind::None;
  }
  return MutationKind::None;
}

}  // namespace erpt
