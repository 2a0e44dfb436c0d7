#include "io/canvas.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "erpt/image_io.h"

namespace erpt {

namespace {

// 5x7 glyphs, one string of 7 rows x 5 columns ('#' = ink) per character.
struct Glyph {
  char c;
  const char* rows;
};
constexpr Glyph kFont[] = {
    {'0', ".###.#...##..###.#.###..##...#.###."}, {'1', "..#...##....#....#....#....#...###."},
    {'2', ".###.#...#....#...#...#...#...#####"}, {'3', "####.....#....#.###.....#....#####."},
    {'4', "...#...##..#.#.#..#.#####...#....#."}, {'5', "######....####.....#....##...#.###."},
    {'6', "..##..#...#....####.#...##...#.###."}, {'7', "#####....#...#...#...#....#....#..."},
    {'8', ".###.#...##...#.###.#...##...#.###."}, {'9', ".###.#...##...#.####....#...#..##.."},
    {'A', ".###.#...##...#######...##...##...#"}, {'B', "####.#...##...#####.#...##...#####."},
    {'C', ".###.#...##....#....#....#...#.###."}, {'D', "###..#..#.#...##...##...##..#.###.."},
    {'E', "######....#....####.#....#....#####"}, {'F', "######....#....####.#....#....#...."},
    {'G', ".###.#...##....#.####...##...#.####"}, {'H', "#...##...##...#######...##...##...#"},
    {'I', ".###...#....#....#....#....#...###."}, {'J', "..###...#....#....#....#.#..#..##.."},
    {'K', "#...##..#.#.#..##...#.#..#..#.#...#"}, {'L', "#....#....#....#....#....#....#####"},
    {'M', "#...###.###.#.##.#.##...##...##...#"}, {'N', "#...##...###..##.#.##..###...##...#"},
    {'O', ".###.#...##...##...##...##...#.###."}, {'P', "####.#...##...#####.#....#....#...."},
    {'Q', ".###.#...##...##...##.#.##..#..##.#"}, {'R', "####.#...##...#####.#.#..#..#.#...#"},
    {'S', ".#####....#.....###.....#....#####."}, {'T', "#####..#....#....#....#....#....#.."},
    {'U', "#...##...##...##...##...##...#.###."}, {'V', "#...##...##...##...##...#.#.#...#.."},
    {'W', "#...##...##...##.#.##.#.##.#.#.#.#."}, {'X', "#...##...#.#.#...#...#.#.#...##...#"},
    {'Y', "#...##...#.#.#...#....#....#....#.."}, {'Z', "#####....#...#...#...#...#....#####"},
    {'.', "..........................##...##.."}, {',', ".....................##....#...#..."},
    {'-', "...............#####..............."}, {'+', ".......#....#..#####..#....#......."},
    {'(', "...#...#...#....#....#.....#.....#."}, {')', ".#.....#.....#....#....#...#...#..."},
    {'/', ".........#...#...#...#...#........."}, {':', "......##...##........##...##......."},
    {'=', "..........#####.....#####.........."}, {'_', "..............................#####"},
    {'%', "##...##..#...#...#...#...#..##...##"}, {'[', ".###..#....#....#....#....#....###."},
    {']', ".###....#....#....#....#....#..###."}, {'^', "..#...#.#.#...#...................."},
    {'*', ".....#.#.#.###.#####.###.#.#.#....."},
};

const char* glyphFor(char c) {
  const char u = char(std::toupper(static_cast<unsigned char>(c)));
  for (const Glyph& g : kFont)
    if (g.c == u) return g.rows;
  return nullptr;
}

}  // namespace

Canvas::Canvas(int width, int height, Rgb8 background)
    : width_(width), height_(height), pixels_(size_t(width) * size_t(height), background) {}

void Canvas::set(int x, int y, Rgb8 c) {
  if (x >= 0 && y >= 0 && x < width_ && y < height_) pixels_[size_t(y) * size_t(width_) + size_t(x)] = c;
}

void Canvas::fillRect(int x0, int y0, int x1, int y1, Rgb8 c) {
  for (int y = std::max(0, std::min(y0, y1)); y <= std::min(height_ - 1, std::max(y0, y1)); ++y)
    for (int x = std::max(0, std::min(x0, x1)); x <= std::min(width_ - 1, std::max(x0, x1)); ++x) set(x, y, c);
}

void Canvas::line(double x0, double y0, double x1, double y1, Rgb8 c, int thickness, int dash) {
  const double length = std::hypot(x1 - x0, y1 - y0);
  const int steps = std::max(1, int(std::ceil(length * 2)));
  const int lo = -(thickness - 1) / 2, hi = thickness / 2;
  for (int i = 0; i <= steps; ++i) {
    const double t = double(i) / steps;
    if (dash > 0 && int(t * length / dash) % 2 == 1) continue;
    const int x = int(std::lround(x0 + t * (x1 - x0))), y = int(std::lround(y0 + t * (y1 - y0)));
    fillRect(x + lo, y + lo, x + hi, y + hi, c);
  }
}

void Canvas::text(int x, int y, const std::string& s, Rgb8 c, int scale) {
  for (size_t k = 0; k < s.size(); ++k) {
    const char* rows = glyphFor(s[k]);
    if (!rows) continue;
    const int gx = x + int(k) * 6 * scale;
    for (int row = 0; row < 7; ++row)
      for (int col = 0; col < 5; ++col)
        if (rows[row * 5 + col] == '#') fillRect(gx + col * scale, y + row * scale, gx + (col + 1) * scale - 1, y + (row + 1) * scale - 1, c);
  }
}

void Canvas::writePng(const std::string& path) const {
  writeRgb8Atomic(path, width_, height_, reinterpret_cast<const uint8_t*>(pixels_.data()));
}

}  // namespace erpt
