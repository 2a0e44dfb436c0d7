// Colour textures: constant, bitmap (linear RGB after sRGB decoding, bilinear) and
// checkerboard, each with Mitsuba's uv transform (scale then offset).
#pragma once

#include <vector>

#include "erpt/math.h"

namespace erpt {

enum class TextureKind { Bitmap, Checkerboard };

struct Texture {
  TextureKind kind = TextureKind::Checkerboard;
  float uScale = 1, vScale = 1, uOffset = 0, vOffset = 0;
  // checkerboard
  Color color0{0.4f}, color1{0.2f};
  // bitmap: row 0 is the image's top row; v = 0 is its bottom (Mitsuba's convention)
  int width = 0, height = 0;
  std::vector<Color> texels;

  Color eval(float u, float v) const;
  // Derivatives of the luminance of eval() with respect to u and v (bump mapping): exact for
  // the bilinear interpolation inside a texel cell; 0 for the checkerboard (piecewise constant).
  void luminanceGradient(float u, float v, float& du, float& dv) const;
};

// A colour parameter: a constant, or a texture from Scene::textures.
struct ColorParam {
  Color value{0.5f};
  int texture = -1;
};

}  // namespace erpt
