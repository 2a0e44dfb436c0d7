// A latitude-longitude environment map (Mitsuba's `envmap`, both dialects): radiance by
// direction, and importance sampling of directions.
//
// Directions map to the image as in Mitsuba 0.6 and 3: in the map's own frame (to_world maps it
// to the world) a unit direction d has u = atan2(d.x, -d.z) / (2 pi) (wrapped to [0, 1)) and
// v = acos(d.y) / pi, so +y is the top row, +z the middle column, +x the column at u = 1/4
// and -z the left and right edges. Radiance is bilinear
// between pixel centres (u repeats, v clamps), times `scale`.
//
// Sampling picks a pixel (marginal over rows, then conditional over the row's pixels) with
// probability P_i proportional to its luminance times sin(theta) at its centre, then moves
// the pixel's centre by a tent-distributed offset of up to one pixel in u and in v (u wraps,
// v reflects at the poles). The density of the sampled point in the pixel grid is then the
// bilinear interpolant of the P_i, the same interpolation as the radiance's, so radiance / pdf
// is about constant over the map, even across a sun a few pixels wide; in solid angle it is
// that interpolant over 2 pi^2 sin(theta) per unit of uv. pdf() returns it for any
// direction, and sample() returns pdf() of the direction it made.
#pragma once

#include <cstdint>
#include <vector>

#include "erpt/image_io.h"
#include "erpt/math.h"

namespace erpt {

class EnvironmentMap {
 public:
  // `image` in linear radiance; throws std::invalid_argument when it has no pixels, a
  // negative or non-finite value, or no light at all.
  EnvironmentMap(const RgbImage& image, float scale, const Transform& toWorld);

  Color eval(Vec3 direction) const;  // radiance arriving from world direction `direction`
  // A unit world direction for (u1, u2) in [0, 1)^2 and its solid-angle pdf (false: pdf 0,
  // only at a pole or at the very end of a pixel's tent);
  // with `radiance`, also eval() of the direction.
  bool sample(float u1, float u2, Vec3& direction, float& pdf, Color* radiance = nullptr) const;
  float pdf(Vec3 direction) const;
  // eval() and pdf() of one direction, from one trip to uv: the inverse trigonometry was a
  // fifth of the path tracer's time under an environment map, and an escaping ray or a
  // sampled direction needs both. The same bits as the two calls.
  Color evalAndPdf(Vec3 direction, float& pdf) const;
  // Radiance averaged over the sphere of directions (the map's power / (4 pi) per unit area).
  Color mean() const { return mean_; }
  int width() const { return width_; }
  int height() const { return height_; }

  // The map's uv of a world direction, and back (exposed for tests).
  void directionToUv(Vec3 direction, float& u, float& v) const;
  Vec3 uvToDirection(float u, float v) const;

  // The map's tables as the vector kernels read them (kernels/environment_map_lanes.h), which
  // compute what sample() and evalAndPdf() compute, eight directions at a time.
  struct Tables {
    int width, height;
    const float* radiance;     // 3 floats per pixel: the scaled radiance, row-major, row 0 = +y
    const float* weight;       // per pixel: the pdf's bilinear weights (weight_)
    const float* rowCdf;       // height + 1 entries
    const float* columnCdf;    // per row: width + 1 entries
    const uint32_t* rowGuide;  // rowBuckets + 1 entries
    const uint32_t* columnGuide;  // per row: columnBuckets + 1 entries
    int rowBuckets, columnBuckets;
    const Vec3* toWorld;  // rotation rows
    const Vec3* toLocal;
  };
  Tables tables() const;

 private:
  // The four pixels around a point of the map and their bilinear weights.
  struct Bilinear {
    int x0, x1, y0, y1;
    float tx, ty;
    template <class T>
    T of(const T* values, int width) const {
      auto at = [&](int px, int py) { return values[size_t(py) * size_t(width) + size_t(px)]; };
      return (at(x0, y0) * (1 - tx) + at(x1, y0) * tx) * (1 - ty) + (at(x0, y1) * (1 - tx) + at(x1, y1) * tx) * ty;
    }
  };
  void directionToUv(Vec3 direction, float& u, float& v, float& sinTheta) const;
  Bilinear bilinearAt(float u, float v) const;
  Color evalAtUv(float u, float v) const;
  float pdfAt(const Bilinear& b, float sinTheta) const;

  int width_, height_;
  std::vector<Color> pixels_;    // scaled radiance, row-major, row 0 = +y
  std::vector<float> rowCdf_;    // height + 1 entries
  std::vector<float> columnCdf_;  // per row: width + 1 entries
  // Guide tables of the CDFs (buckets + 1 entries each; environment_map.cpp's pickInterval).
  size_t rowBuckets_ = 1, columnBuckets_ = 1;
  std::vector<uint32_t> rowGuide_, columnGuide_;
  std::vector<float> weight_;    // per pixel: P_i W H / (2 pi^2), whose bilinear interpolant over sin(theta) is the pdf
  Color mean_;
  Vec3 toWorld_[3], toLocal_[3];  // rotation rows (to_world's 3x3, orthonormalised)
};

}  // namespace erpt
