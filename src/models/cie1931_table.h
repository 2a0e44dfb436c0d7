// The CIE 1931 2-degree colour matching functions, tabulated by the CIE at 5 nm steps.
#pragma once

namespace erpt {

struct Cie1931Sample {
  double x, y, z;
};

constexpr int kCie1931First = 360;  // nm of the first row
constexpr int kCie1931Step = 5;     // nm between rows
constexpr int kCie1931Rows = 95;    // 360 to 830 nm
extern const Cie1931Sample kCie1931[kCie1931Rows];

}  // namespace erpt
