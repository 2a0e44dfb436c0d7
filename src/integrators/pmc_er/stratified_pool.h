// PMC-ER's pool of stratified film positions (paper section 4.5): every pixel sample of the
// whole render, handed out once each, in an order that covers the image evenly at any time.
// Position k is sample number r = k / pixels of pixel perm_r(k mod pixels), perm_r a
// pseudo-random permutation of the pixels for round r; sample r of a pixel falls in its x
// stratum r and a permuted y stratum (the path tracer's stratification, stages.h), so the
// positions of a pixel are stratified and no position is used twice. Nothing is stored: a
// position is computed from its index.
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/rng.h"

namespace erpt {

struct StratifiedPool {
  uint32_t pixels = 0;  // width * height
  uint32_t spp = 0;     // samples per pixel: the pool has pixels * spp positions
  uint64_t seed = 0;    // chooses the permutations

  size_t size() const { return size_t(pixels) * spp; }
  void at(size_t k, uint32_t& pixel, uint32_t& sample) const {
    const uint32_t round = uint32_t(k / pixels);
    sample = round;
    pixel = permuteIndex(uint32_t(k % pixels), pixels, uint32_t(streamKey(seed, 0x706f6f6cull, round)));
  }
};

// Some rounds of a pool: `count` rounds first, first + stride, ... (a group of sample passes
// of one rank: sample_passes.h). Position k of the rounds is position index(k) of the pool.
struct PoolRounds {
  StratifiedPool pool;
  uint32_t first = 0, stride = 1, count = 0;

  static PoolRounds all(const StratifiedPool& pool) { return PoolRounds{pool, 0, 1, pool.spp}; }
  size_t size() const { return size_t(pool.pixels) * count; }
  size_t index(size_t k) const {
    return size_t(first + stride * uint32_t(k / pool.pixels)) * pool.pixels + k % pool.pixels;
  }
  void at(size_t k, uint32_t& pixel, uint32_t& sample) const { pool.at(index(k), pixel, sample); }
};

}  // namespace erpt
