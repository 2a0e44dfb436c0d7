// Inverting a discrete CDF: the index std::upper_bound finds (the first entry greater than u)
// in a non-decreasing array, found without branches. Sampling searches with random numbers,
// so a branchy binary search's comparisons go either way at random and the processor guesses
// about half of them wrong; here each halving step is a conditional move. Every comparison is
// the one std::upper_bound makes (u against an entry, in the wider of the two types), so the
// index is the same for every u.
#pragma once

#include <cstddef>

namespace erpt {

template <class Entry, class Value>
size_t upperBoundIndex(const Entry* sorted, size_t n, Value u) {
  if (n == 0) return 0;
  size_t low = 0;  // the answer lies in [low, low + n]
  while (n > 1) {
    const size_t half = n / 2;
    low = sorted[low + half - 1] <= u ? low + half : low;
    n -= half;
  }
  return low + (sorted[low] <= u ? 1 : 0);
}

}  // namespace erpt
