// The Hosek-Wilkie sky model's RGB coefficient data (defined in hosek_wilkie_rgb_data.cpp).
#pragma once

namespace erpt {

// Per channel: [albedo 0, 1][turbidity 1..10][6 Bezier control points][9 parameters].
extern const double kHosekWilkieRgbCoefficients[3][1080];
// Per channel: [albedo 0, 1][turbidity 1..10][6 Bezier control points] radiance scales.
extern const double kHosekWilkieRgbRadiance[3][120];

}  // namespace erpt
