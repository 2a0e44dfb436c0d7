// Spectra to linear sRGB, the way Mitsuba 0.6's RGB build converts them: XYZ by the CIE 1931
// 2-degree matching functions over 360-830 nm, divided by the integral of y-bar (a flat
// spectrum of value v has Y = v), then the sRGB primaries.
#pragma once

#include <functional>

#include "erpt/math.h"

namespace erpt {

// `radiance(nm)`: a spectral quantity as a function of wavelength in nanometres. The matching
// functions are the analytic multi-lobe fit of Wyman, Sloan and Shirley (2013), within about
// 1% of the tabulated CIE 1931 functions; the integral is a sum at 1 nm steps.
Color spectrumToLinearRgb(const std::function<double(double)>& radiance);

}  // namespace erpt
