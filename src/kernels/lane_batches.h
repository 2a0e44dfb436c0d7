// The loop of a vector kernel over n items: whole batches of `lanes` straight from the
// arrays, then the tail through the same batch code on zero-padded copies, so every item gets
// identical math whatever its position (camera_rays.cpp, sphere_coordinates.cpp).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>

namespace erpt {

// batch(in, out) reads `lanes` floats from each in[c] and writes `lanes` to each out[c].
template <size_t lanes, size_t kIn, size_t kOut, class Batch>
void forEachLaneBatch(size_t n, const std::array<const float*, kIn>& in, const std::array<float*, kOut>& out,
                      Batch&& batch) {
  auto offset = [](auto columns, size_t i) {
    for (auto& c : columns) c += i;
    return columns;
  };
  size_t i = 0;
  for (; i + lanes <= n; i += lanes) batch(offset(in, i), offset(out, i));
  if (i == n) return;
  float padIn[kIn][lanes] = {}, padOut[kOut][lanes];
  std::array<const float*, kIn> tailIn;
  std::array<float*, kOut> tailOut;
  for (size_t c = 0; c < kIn; ++c) {
    std::copy(in[c] + i, in[c] + n, padIn[c]);
    tailIn[c] = padIn[c];
  }
  for (size_t c = 0; c < kOut; ++c) tailOut[c] = padOut[c];
  batch(tailIn, tailOut);
  for (size_t c = 0; c < kOut; ++c) std::copy(padOut[c], padOut[c] + (n - i), out[c] + i);
}

}  // namespace erpt
