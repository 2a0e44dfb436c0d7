#include "integrators/noise_filters.h"

#include <algorithm>
#include <cmath>

#include "erpt/error.h"

namespace erpt {

std::vector<float> expectedProposals(const std::vector<uint32_t>& tally, int width, int height, int radius) {
  const size_t w = size_t(width), h = size_t(height);
  if (tally.size() != w * h) throw UsageError("proposal tally does not match the image size");
  // Summed-area table with a zero first row and column: any window sum in four lookups.
  std::vector<double> sat((w + 1) * (h + 1), 0.0);
  for (size_t y = 0; y < h; ++y)
    for (size_t x = 0; x < w; ++x)
      sat[(y + 1) * (w + 1) + x + 1] =
          double(tally[y * w + x]) + sat[y * (w + 1) + x + 1] + sat[(y + 1) * (w + 1) + x] - sat[y * (w + 1) + x];
  std::vector<float> out(w * h);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const size_t x0 = size_t(std::max(0, x - radius)), x1 = size_t(std::min(width, x + radius + 1));
      const size_t y0 = size_t(std::max(0, y - radius)), y1 = size_t(std::min(height, y + radius + 1));
      const double sum = sat[y1 * (w + 1) + x1] - sat[y0 * (w + 1) + x1] - sat[y1 * (w + 1) + x0] + sat[y0 * (w + 1) + x0];
      out[size_t(y) * w + size_t(x)] = float(sum / double((x1 - x0) * (y1 - y0)));
    }
  return out;
}

RgbImage applyProposalFilter(const RgbImage& image, const std::vector<uint32_t>& tally, int radius) {
  const std::vector<float> expected = expectedProposals(tally, image.width, image.height, radius);
  RgbImage out = image;
  for (size_t i = 0; i < out.pixels.size(); ++i)
    if (tally[i] > 0) out.pixels[i] = out.pixels[i] * (expected[i] / float(tally[i]));
  return out;
}

RgbImage proposalFilteredImage(const RgbImage& raw, const RgbImage& chains, const RgbImage& proposals, int radius) {
  std::vector<uint32_t> tally(proposals.pixels.size());
  for (size_t i = 0; i < tally.size(); ++i) tally[i] = uint32_t(std::lround(std::max(0.0f, proposals.pixels[i].x)));
  RgbImage out = applyProposalFilter(chains, tally, radius);
  for (size_t i = 0; i < out.pixels.size(); ++i) out.pixels[i] += raw.pixels[i] - chains.pixels[i];
  return out;
}

}  // namespace erpt
