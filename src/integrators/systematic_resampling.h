// Systematic resampling, the one resampler: PMC-ER's members and candidates by their remaining
// energy into the population's slots (paper section 4.5 as an unbiased rule, docs/pmc-er.md),
// and MLT's chain starts from the bootstrap's paths by luminance (docs/mlt.md). Items are
// resampled into a fixed number of slots. Item i gets counts[i] copies, each carrying energy W / slots (W: the total),
// with E[counts[i]] = slots * w_i / W exactly, so every item's expected energy is kept
// (E[counts[i] W / slots] = w_i) and the total is kept exactly. An item with w_i < W / slots
// survives with probability proportional to its energy (Russian roulette); a larger one is
// split into several copies, which then move on independently.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace erpt {

// `u` in [0, 1): the one random number of the comb. Weights must be finite and >= 0; with a
// zero total every count is 0.
std::vector<uint32_t> systematicCounts(const std::vector<double>& weights, size_t slots, double u);
// The same comb as ordinals: `slots` item indices in increasing order, item i repeated counts[i] times.
std::vector<size_t> systematicPicks(const std::vector<double>& weights, size_t slots, double u);

}  // namespace erpt
