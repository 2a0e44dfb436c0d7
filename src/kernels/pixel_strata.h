// Where in its pixel each camera sample lands, before the pixel filter: sample s of a pixel
// takes stratum permuteIndex(s) in x and another in y (a Latin hypercube per pixel and per
// block of spp samples, generate_camera_rays.cpp) plus a uniform offset within it. Each
// sample is eleven 64-bit hashes and two permutations, a scalar chain of about a hundred
// multiplies; here AVX2 lanes compute the same numbers bit for bit, four and eight at a time.
#pragma once

#include <cstddef>
#include <cstdint>

namespace erpt {

// ux[i], uy[i] in [0, 1) for sample samples[i] of pixel pixels[i], i < n, with `spp` samples
// per pixel and film dimensions `dimX`, `dimY` of each sample's stream.
void pixelStrata(uint64_t seed, uint32_t spp, uint32_t dimX, uint32_t dimY, const uint32_t* pixels,
                 const uint32_t* samples, size_t n, float* ux, float* uy);

}  // namespace erpt
