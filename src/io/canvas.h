// A small 8-bit RGB drawing surface for the project's own charts and heat maps (`erpt compare`
// plots, `erpt diff --heatmap`), written as PNG through OpenImageIO: no plotting program needed.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace erpt {

struct Rgb8 {
  uint8_t r = 0, g = 0, b = 0;
};

class Canvas {
 public:
  Canvas(int width, int height, Rgb8 background);
  int width() const { return width_; }
  int height() const { return height_; }
  Rgb8 at(int x, int y) const { return pixels_[size_t(y) * size_t(width_) + size_t(x)]; }
  void set(int x, int y, Rgb8 c);  // ignores points outside
  void fillRect(int x0, int y0, int x1, int y1, Rgb8 c);  // inclusive corners, clipped
  // A line `thickness` pixels wide; `dash` > 0 draws dashes of that many pixels.
  void line(double x0, double y0, double x1, double y1, Rgb8 c, int thickness = 1, int dash = 0);
  // Text in a built-in 5x7 pixel font (upper case; lower case is drawn as upper case),
  // `scale` pixels per font pixel, top-left corner at (x, y). Unknown characters are blanks.
  void text(int x, int y, const std::string& s, Rgb8 c, int scale = 1);
  static int textWidth(const std::string& s, int scale = 1) { return int(s.size()) * 6 * scale - scale; }
  static int textHeight(int scale = 1) { return 7 * scale; }
  // Writes a PNG (atomically, like every image of the project).
  void writePng(const std::string& path) const;

 private:
  int width_, height_;
  std::vector<Rgb8> pixels_;
};

}  // namespace erpt
