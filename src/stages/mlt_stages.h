// The stage kernels MLT adds to the chain step (docs/mlt.md): its choice between a large step
// and ERPT's perturbations, and the stage that turns the path-tracer samples of the large steps
// into proposals.
#pragma once

#include <cstdint>

#include "stages/chain_stages.h"
#include "mutations/large_step.h"

namespace erpt {

// MLT's mutation choice: with probability ctx.largeSteps->probability (a coin on the chain's
// stream, the same for every path, so it cancels in the acceptance ratio) a large step (state
// kProposalLarge, no ray), else ERPT's perturbation for the path's signature.
const ProposalPolicy& mltChooser();

// Whether the chains hold path `path` (their domain): a vertex count the large step draws, no
// directional light, positive finite f in every mutation measure the strategy may pick, and a
// positive large-step weight W, which it returns (0: outside). The bootstrap sorts its samples
// by it and the large step rejects what lies outside, so the chains and the bootstrap's
// in-place estimate share every path exactly once.
float mltDomainWeight(const StepConfig& ctx, const PathVertex* path, int n, float filmX, float filmY);
// The same test, saying why a path lies outside (kInPlaceReasonCount: inside, with W in `w`).
InPlaceReason mltDomainReason(const StepConfig& ctx, const PathVertex* path, int n, float filmX, float filmY, float& w);

// The path-tracer sample of the large step of chain `slot`: a pixel uniform over the image
// and a sample number hashed from the chain's key and step (its random stream is then
// streamKey(large-step seed, pixel, sample)).
void largeStepSample(const ChainQueue& chains, size_t slot, uint32_t pixels, uint32_t& pixel, uint32_t& sample);

// What the large step of chain `slot` asks of its sample: the vertex count n (drawn with
// P(n)) and whether the next-event technique's candidate (drawn with P(nee | n)).
void largeStepTarget(const LargeStepModel& m, const ChainQueue& chains, size_t slot, int& vertices, bool& nee);

// The large steps' proposals: `samples` holds what the path tracer recorded for sample k of
// [0, count) (SeedQueue::path = k), made for chain slot slotOf[k]. Each chain draws a vertex
// count n (P(n)) and a technique (P(nee | n)) and proposes that candidate, if the sample made
// it and it lies in the domain; else its proposal is rejected.
void stageMltLargeSteps(const StepConfig& ctx, const ChainQueue& chains, const SeedStore& samples,
                        const uint32_t* slotOf, size_t count, ProposalQueue& proposals, VertexQueue& proposalVertices);

}  // namespace erpt
