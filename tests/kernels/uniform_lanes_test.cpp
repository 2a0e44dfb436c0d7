// The lane generator returns uniformFloat's numbers bit for bit (the diffuse shade kernel
// relies on it: its paths must draw what the scalar body would), for any count, including
// the tail that does not fill a vector.
#include <gtest/gtest.h>

#include <vector>

#include "core/rng.h"
#include "kernels/uniform_lanes.h"

namespace erpt {
namespace {

TEST(UniformLanes, SameNumbersAsUniformFloatForEveryCount) {
  size_t checked = 0;
  for (size_t n = 0; n <= 37; ++n) {
    std::vector<uint64_t> offset(n);
    std::vector<uint32_t> dims(n);
    std::vector<uint64_t> keys(n);
    for (size_t j = 0; j < n; ++j) {
      keys[j] = streamKey(3, n, j);
      dims[j] = uint32_t(uniformIndex(keys[j], 0, 1u << 20)) * (j % 3 == 0 ? 4096u : 1u);  // large dims too
      offset[j] = dimensionOffset(keys[j], dims[j]);
    }
    std::vector<float> out(n + 1, -1.0f);
    uniformFloatsAt(offset.data(), n, out.data());
    for (size_t j = 0; j < n; ++j) {
      ASSERT_EQ(out[j], uniformFloat(keys[j], dims[j])) << "n " << n << ", lane " << j;
      ++checked;
    }
    EXPECT_EQ(out[n], -1.0f) << "wrote past n = " << n;
  }
  EXPECT_EQ(checked, 37u * 38u / 2u);
}

}  // namespace
}  // namespace erpt
