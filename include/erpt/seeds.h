// The seed store: every contributing light connection the path tracer made, as a complete
// path with the densities it was sampled with (ERPT paper, section 4.1). ERPT starts its
// Markov chains from these. Seeds are appended in a fixed order (batch, bounce, path), so the
// store is identical for any thread count.
#pragma once

#include "erpt/queues.h"

namespace erpt {

struct SeedStore {
  SeedQueue seeds;
  VertexQueue vertices;

  size_t size() const { return seeds.size(); }
  // X_f: what this seed added to the path-traced image (MIS weight * unweighted estimate).
  Color contribution(size_t i) const {
    return Color(seeds.estimateR[i], seeds.estimateG[i], seeds.estimateB[i]) * seeds.misWeight[i];
  }
  void clear() {
    seeds.resize(0);
    vertices.resize(0);
  }
};

}  // namespace erpt
