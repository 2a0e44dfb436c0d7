// The lanes of pixelStrata give the scalar definition's numbers bit for bit: for spp that are
// and are not powers of two (the permutation retries outside [0, spp)), for samples past spp
// (later blocks), for large pixel indices, and for counts with a tail that fills no vector.
#include <gtest/gtest.h>

#include <vector>

#include "core/rng.h"
#include "kernels/pixel_strata.h"

namespace erpt {
namespace {

TEST(PixelStrata, LanesMatchTheScalarDefinition) {
  size_t checked = 0;
  for (uint32_t spp : {1u, 2u, 3u, 7u, 16u, 100u, 4097u, 1u << 20}) {
    for (size_t n : {0, 5, 8, 37, 200}) {
      std::vector<uint32_t> pixels(n), samples(n);
      for (size_t i = 0; i < n; ++i) {
        const uint64_t key = streamKey(5, spp, i);
        pixels[i] = i % 3 == 0 ? uint32_t(uniformUint(key, 0)) : uint32_t(uniformIndex(key, 0, 4096));
        samples[i] = i % 4 == 0 ? uint32_t(uniformIndex(key, 1, 50 * uint64_t(spp))) : uint32_t(uniformIndex(key, 1, spp));
      }
      std::vector<float> ux(n + 1, -1.0f), uy(n + 1, -1.0f);
      pixelStrata(9, spp, 0, 1, pixels.data(), samples.data(), n, ux.data(), uy.data());
      for (size_t i = 0; i < n; ++i) {
        const uint64_t key = streamKey(9, pixels[i], samples[i]);
        const uint32_t block = samples[i] / spp, s = samples[i] % spp;
        const uint32_t keyX = uint32_t(streamKey(9, pixels[i], ~1ull - 2 * uint64_t(block))),
                       keyY = uint32_t(streamKey(9, pixels[i], ~0ull - 2 * uint64_t(block)));
        ASSERT_EQ(ux[i], (float(permuteIndex(s, spp, keyX)) + uniformFloat(key, 0)) / float(spp))
            << "spp " << spp << ", n " << n << ", sample " << i;
        ASSERT_EQ(uy[i], (float(permuteIndex(s, spp, keyY)) + uniformFloat(key, 1)) / float(spp))
            << "spp " << spp << ", n " << n << ", sample " << i;
        ++checked;
      }
      EXPECT_EQ(ux[n], -1.0f) << "wrote past n = " << n;
      EXPECT_EQ(uy[n], -1.0f) << "wrote past n = " << n;
    }
  }
  EXPECT_EQ(checked, 8u * (5 + 8 + 37 + 200));
}

}  // namespace
}  // namespace erpt
