// Black bodies as Mitsuba 0.6 loads `<blackbody temperature="..." scale="..."/>` in its RGB
// build: Planck's law in W / (m^2 sr nm), integrated against the CIE 1931 matching functions
// over 360-830 nm, divided by the integral of y-bar there (so Y is the y-bar-weighted mean
// spectral radiance, no 683 lm/W), then linear sRGB (Rec. 709 primaries), negatives clamped.
// A 3500 K lamp is thus about (2173, 1239, 564): scenes bring it down with `scale`.
#pragma once

#include "erpt/math.h"

namespace erpt {

// Spectral radiance of a black body at `kelvin`, wavelength `nm`, in W / (m^2 sr nm).
double planckRadiance(double nm, double kelvin);

// The linear sRGB colour of that radiance, as above (times no scale).
Color blackbodyLinearRgb(double kelvin);

}  // namespace erpt
