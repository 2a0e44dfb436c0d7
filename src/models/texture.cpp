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

void Texture::luminanceGradient(float u, float v, float& du, float& dv) const {
  du = dv = 0;
  if (kind == TextureKind::Checkerboard) return;
  // The same cell as eval(); x grows with u, y (image rows) shrinks as v grows.
  const float x = (u * uScale + uOffset) * width - 0.5f, y = (1.0f - (v * vScale + vOffset)) * height - 0.5f;
  const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
  const float fx = x - x0, fy = y - y0;
  auto at = [&](int xi, int yi) { return luminance(texels[size_t(wrap(yi, height)) * width + wrap(xi, width)]); };
  const float a = at(x0, y0), b = at(x0 + 1, y0), c = at(x0, y0 + 1), d = at(x0 + 1, y0 + 1);
  const float dfx = (b - a) * (1 - fy) + (d - c) * fy, dfy = (c * (1 - fx) + d * fx) - (a * (1 - fx) + b * fx);
  du = dfx * float(width) * uScale;
  dv = -dfy * float(height) * vScale;
}

}  // namespace erpt
