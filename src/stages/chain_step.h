// One step of every chain in an StepQueues, the only implementation of the protocol
//   mutate -> (intersect -> trace)* -> manifold -> connect -> accept
// (chain_stages.h), used by the ERPT chain machine, the stage tests and the benchmark. Each
// stage runs over the whole queue split into ranges across threads; intersect and connect hand
// Embree only the ranges that have rays in flight. The deposit records are left in the
// queue's deposit rows for the caller (the chain machine applies them to the film in slot
// order, so the image does not depend on the thread count).
#pragma once

#include <cstdint>

#include "stages/chain_stages.h"
#include "core/parallel.h"
#include "tracer/tracer.h"

namespace erpt {

struct ChainStep {
  const Tracer& tracer;
  const StepConfig& ctx;
  StageTimes* times = nullptr;  // per-stage seconds, when set
  size_t grain = 256;           // slots per range
  const ProposalPolicy* policy = nullptr;  // the integrator's choices; null: ERPT's (erptChooser)

  // mutate -> (intersect -> trace)* -> manifold -> connect; returns the rays traced.
  uint64_t propose(StepQueues& q) const;
  // (intersect -> trace)* -> connect for proposals already started (their first rays set):
  // propose() after mutate, and tests that aim a proposal by hand (a reverse move).
  uint64_t traceAndConnect(StepQueues& q) const;
  // accept (and the step's deposit records).
  void accept(StepQueues& q, StepCounters& counters) const;
  uint64_t run(StepQueues& q, StepCounters& counters) const {
    const uint64_t rays = propose(q);
    accept(q, counters);
    return rays;
  }
};

}  // namespace erpt
