// Pixels visited in 16x16 tiles, row by row inside a tile: neighbouring camera rays are
// then neighbours in the queue, which is what makes the coherent stream flag pay.
#pragma once

#include <cstdint>
#include <vector>

namespace erpt {

inline std::vector<uint32_t> tiledPixelOrder(int width, int height, int tile = 16) {
  std::vector<uint32_t> order;
  order.reserve(size_t(width) * height);
  for (int ty = 0; ty < height; ty += tile)
    for (int tx = 0; tx < width; tx += tile)
      for (int y = ty; y < std::min(height, ty + tile); ++y)
        for (int x = tx; x < std::min(width, tx + tile); ++x) order.push_back(uint32_t(y) * uint32_t(width) + uint32_t(x));
  return order;
}

}  // namespace erpt
