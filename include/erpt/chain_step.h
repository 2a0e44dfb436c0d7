// One step of every chain in an ErptQueues, the only implementation of the protocol
//   mutate -> (intersect -> trace)* -> connect -> accept
// (erpt_stages.h), used by the ERPT chain machine, the stage tests and the benchmark. Each
// stage runs over the whole queue split into ranges across threads; intersect and connect hand
// Embree only the ranges that have rays in flight. The deposit records are left in the
// queue's deposit rows for the caller (the chain machine applies them to the film in slot
// order, so the image does not depend on the thread count).
#pragma once

#include <cstdint>

#include "erpt/erpt_stages.h"
#include "erpt/parallel.h"
#include "erpt/tracer.h"

namespace erpt {


// Proposals made outside the mutation units: MLT's large steps. After the mutate stage, the
// slots in state kProposalLarge wait for it; it must leave each complete (the whole proposed
// path in the slot's proposal vertex rows, its vertex count, signature, film position, colour
// and W(z)) or rejected. Returns the rays it traced.
class ProposalSource {
 public:
  virtual ~ProposalSource() = default;
  virtual uint64_t propose(const ErptStepContext& ctx, ErptQueues& q, StageTimes* times) const = 0;
};

struct ChainStep {
  const Tracer& tracer;
  const ErptStepContext& ctx;
  StageTimes* times = nullptr;  // per-stage seconds, when set
  size_t grain = 256;           // slots per range
  const MutationChooser* chooser = nullptr;  // the mutate stage's choice; null: ERPT's (erptChooser)
  const ProposalSource* largeSteps = nullptr;  // MLT: makes the large steps the chooser picked

  // mutate -> (intersect -> trace)* -> connect; returns the rays traced.
  uint64_t propose(ErptQueues& q) const;
  // (intersect -> trace)* -> connect for proposals already started (their first rays set):
  // propose() after mutate, and tests that aim a proposal by hand (a reverse move).
  uint64_t traceAndConnect(ErptQueues& q) const;
  // accept (and the step's deposit records).
  void accept(ErptQueues& q, ErptCounters& counters) const;
  uint64_t run(ErptQueues& q, ErptCounters& counters) const {
    const uint64_t rays = propose(q);
    accept(q, counters);
    return rays;
  }
};

}  // namespace erpt
