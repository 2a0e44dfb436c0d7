// The seed store: every contributing light connection the path tracer made, as a complete
// path with the densities it was sampled with (ERPT paper, section 4.1). ERPT starts its
// Markov chains from these. Seeds are appended in a fixed order (batch, bounce, path), so the
// store is identical for any thread count.
#pragma once

#include "core/queues.h"

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
  // Appends every seed of `from` with its vertices (one resize of each queue).
  void appendAll(const SeedStore& from) {
    const size_t seedBase = seeds.size(), vertexBase = vertices.size();
    seeds.resize(seedBase + from.seeds.size());
    vertices.resize(vertexBase + from.vertices.size());
    for (size_t i = 0; i < from.vertices.size(); ++i) {
      vertices.copyRow(vertexBase + i, from.vertices, i);
      if (vertices.parent[vertexBase + i] >= 0) vertices.parent[vertexBase + i] += int32_t(vertexBase);
    }
    for (size_t i = 0; i < from.seeds.size(); ++i) {
      seeds.copyRow(seedBase + i, from.seeds, i);
      seeds.vertexBegin[seedBase + i] += uint32_t(vertexBase);
    }
  }
  // Appends `copies` rows of seed i of `from`, sharing one copy of its vertices.
  void append(const SeedStore& from, size_t i, size_t copies = 1) {
    const size_t begin = vertices.size(), n = from.seeds.vertexCount[i];
    vertices.resize(begin + n);
    for (size_t j = 0; j < n; ++j) vertices.copyRow(begin + j, from.vertices, from.seeds.vertexBegin[i] + j);
    for (size_t c = 0; c < copies; ++c) {
      const size_t row = seeds.size();
      seeds.resize(row + 1);
      seeds.copyRow(row, from.seeds, i);
      seeds.vertexBegin[row] = uint32_t(begin);
    }
  }
};

}  // namespace erpt
