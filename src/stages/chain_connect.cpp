// Connect stage: the connection rays of the proposals that reached their last
// regenerated vertex go to Embree as one occlusion stream; blocked connections reject.
#include "stages/chain_stages.h"

namespace erpt {

void stageChainConnect(const Tracer& tracer, RayQueue& shadowRays, ProposalQueue& proposals, IndexRange range,
                      const uint32_t* slotOf) {
  size_t traced = 0;
  for (size_t k = range.begin; k < range.end; ++k) traced += shadowRays.tnear[k] <= shadowRays.tfar[k];
  // Ranges without a connection are not handed to Embree.
  if (traced > 0) tracer.occluded(shadowRays, range);
  for (size_t k = range.begin; k < range.end; ++k) {
    const size_t i = slotOf ? slotOf[k] : k;
    if (proposals.state[i] != kProposalConnecting) continue;
    if (shadowRays.tfar[k] >= 0) {
      proposals.state[i] = kProposalComplete;
    } else {
      proposals.state[i] = kProposalRejected;
      proposals.reason[i] = kRejectOccluded;
    }
  }
}

}  // namespace erpt
