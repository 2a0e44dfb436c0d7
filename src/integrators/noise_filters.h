// The proposed-mutations noise filter of the ERPT paper (section 4.4), applied once the chains
// are done. Biased (the paper says so too): off unless asked for.
#pragma once

#include <cstdint>
#include <vector>

#include "erpt/image_io.h"

namespace erpt {

// The "expected proposed mutations" image: `tally` (width x height counts) box-blurred over a
// (2 radius + 1)^2 window. Near the border the window is cut to the image and the mean is taken
// over the pixels it keeps, so a constant tally stays constant.
std::vector<float> expectedProposals(const std::vector<uint32_t>& tally, int width, int height, int radius);

// Scales every pixel of `image` by expected / actual proposed mutations. Pixels no proposal
// reached keep their value (there is nothing to compare with).
RgbImage applyProposalFilter(const RgbImage& image, const std::vector<uint32_t>& tally, int radius);

// The filtered render from ERPT's extra images (render.h): `chains` (what the chains
// deposited) rescaled by the tally `proposals`, plus the rest of `raw` (the direct pass).
// Time-budgeted renders call it on their accumulated images: the filter is not linear, so
// it must see the whole tally, not one pass's.
RgbImage proposalFilteredImage(const RgbImage& raw, const RgbImage& chains, const RgbImage& proposals, int radius);

}  // namespace erpt
