// A standard normal number from 64 random bits by Marsaglia and Tsang's ziggurat (2000), with
// 128 layers: most draws are one table lookup, a compare and a multiply, where Box-Muller needs
// a logarithm and a cosine. mmlt's small steps draw one per primary number they move.
//
// Exactly symmetric: the sign is its own bit and the magnitude comes from 31 other bits, so z
// and -z are equally likely (a Metropolis proposal must be symmetric). The layer index comes
// from further bits, apart from the magnitude's (the original's low bits served both). The
// rare draws outside a layer's rectangle take more numbers from a counter-based stream of the
// 64 bits, so the result is a pure function of them.
#pragma once

#include <cstdint>

namespace erpt {

double standardNormalFromBits(uint64_t bits);

}  // namespace erpt
