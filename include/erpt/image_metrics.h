// Image error metrics (what `erpt diff`, `erpt compare` and the statistical tests report).
#pragma once

#include <string>

#include <cstddef>

#include "erpt/image_io.h"

namespace erpt {

struct ImageComparison {
  double mse = 0;          // mean over pixels and channels of (x - r)^2
  double relMse = 0;       // mean over pixels and channels of (x - r)^2 / (r^2 + 0.01)
  Color mean, referenceMean;
  size_t nonFinite = 0;    // pixels of the image with a NaN or Inf channel (left out of the sums)
  // Pixels exactly black (all channels 0) in the image and in the reference where the
  // reference is not: light transport the sampler did not find there at all.
  size_t black = 0, blackWhereReferenceIsNot = 0;
};

Color meanOf(const RgbImage& img);
// The reference box-downsampled to the image's size when its size is an integer multiple of
// it (the same image if the sizes agree). Throws UsageError otherwise.
RgbImage matchReferenceSize(const RgbImage& reference, int width, int height);
// What matchReferenceSize does to a reference of another size, as one sentence for the user
// ("" when the sizes agree): the errors are then against the box-averaged reference.
std::string referenceSizeNote(const RgbImage& reference, int width, int height);
// Compares `img` with `reference` (downsampled as above).
ImageComparison compareImages(const RgbImage& img, const RgbImage& reference);

}  // namespace erpt
