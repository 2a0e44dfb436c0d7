#include "erpt/texture.h"

namespace erpt {

namespace {
// Repeat wrapping, as Mitsuba's bitmap texture does by default.
int wrap(int i, int n) {
  int r = i % n;
  return r < 0 ? r + n : r;
}
}  // namespace

Color Texture::eval(float u, float v) const {
  u = u * uScale + uOffset;
  v = v * vScale + vOffset;
  if (kind == TextureKind::Checkerboard) {
    // Mitsuba: 2x2 checks per unit uv square.
    int iu = int(std::floor(u * 2.0f)), iv = int(std::floor(v * 2.0f));
    return ((iu + iv) & 1) == 0 ? color0 : color1;
  }
  // Texel centres sit at half-integers; v runs bottom to top.
  float x = u * width - 0.5f, y = (1.0f - v) * height - 0.5f;
  int x0 = int(std::floor(x)), y0 = int(std::floor(y));
  float fx = x - x0, fy = y - y0;
  auto at = [&](int xi, int yi) { return texels[size_t(wrap(yi, height)) * width + wrap(xi, width)]; };
  return (at(x0, y0) * (1 - fx) + at(x0 + 1, y0) * fx) * (1 - fy) +
         (at(x0, y0 + 1) * (1 - fx) + at(x0 + 1, y0 + 1) * fx) * fy;
}

}  // namespace erpt
