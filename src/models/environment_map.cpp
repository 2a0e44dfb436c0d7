#include "erpt/environment_map.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/cdf_search.h"

namespace erpt {

namespace {

// Buckets of a CDF's guide: a power of two (so that u * buckets and k / buckets are exact in
// float), about one per four intervals, at most 1024.
size_t guideBuckets(size_t n) {
  size_t g = 1;
  while (g < n / 4 && g < 1024) g *= 2;
  return g;
}

// guide[k] = upperBoundIndex(cdf, n + 1, k / buckets), k = 0 .. buckets.
void buildGuide(const float* cdf, size_t n, size_t buckets, uint32_t* guide) {
  for (size_t k = 0; k <= buckets; ++k) guide[k] = uint32_t(upperBoundIndex(cdf, n + 1, float(k) / float(buckets)));
}

// Index of the interval of `cdf` (n + 1 increasing entries from 0 to 1) that holds u, and u's
// position within it in [0, 1). The guide narrows the search: for u in bucket b = floor(u G),
// b / G <= u < (b + 1) / G, so the first entry above u lies in [guide[b], guide[b + 1]] and
// the search there finds the index a search of the whole CDF finds.
size_t pickInterval(const float* cdf, size_t n, const uint32_t* guide, size_t buckets, float u, float& within) {
  const size_t b = std::min(buckets - 1, size_t(u * float(buckets)));
  const size_t lo = guide[b], hi = guide[b + 1];
  size_t i = lo + upperBoundIndex(cdf + lo, hi - lo, u);
  i = std::min(n - 1, i > 0 ? i - 1 : 0);
  // Skip empty intervals the search may land on (u at a boundary of zero-probability cells).
  while (i + 1 < n && !(cdf[i + 1] > cdf[i])) ++i;
  const float width = cdf[i + 1] - cdf[i];
  within = width > 0 ? std::clamp((u - cdf[i]) / width, 0.0f, 0x1.fffffep-1f) : 0.5f;
  return i;
}

Vec3 rowTimes(const Vec3 rows[3], Vec3 v) { return {dot(rows[0], v), dot(rows[1], v), dot(rows[2], v)}; }

}  // namespace

EnvironmentMap::EnvironmentMap(const RgbImage& image, float scale, const Transform& toWorld)
    : width_(image.width), height_(image.height) {
  if (width_ <= 0 || height_ <= 0 || image.pixels.size() != size_t(width_) * size_t(height_))
    throw std::invalid_argument("the environment image has no pixels");
  if (!(scale >= 0) || !std::isfinite(scale)) throw std::invalid_argument("envmap scale must be finite and >= 0");
  // The rotation part of to_world, orthonormalised (Mitsuba allows only rotations here).
  Vec3 x = normalize(toWorld.vector({1, 0, 0})), y = toWorld.vector({0, 1, 0});
  y = normalize(y - x * dot(x, y));
  const Vec3 z = cross(x, y);
  if (!isFinite(x) || !isFinite(y) || !isFinite(z)) throw std::invalid_argument("envmap to_world is not a rotation");
  const float handed = dot(z, toWorld.vector({0, 0, 1})) < 0 ? -1.0f : 1.0f;
  const Vec3 columns[3] = {x, y, z * handed};
  for (int r = 0; r < 3; ++r) {
    toWorld_[r] = Vec3(columns[0][r], columns[1][r], columns[2][r]);
    toLocal_[r] = columns[r];
  }

  pixels_.resize(image.pixels.size());
  for (size_t i = 0; i < pixels_.size(); ++i) {
    const Color c = image.pixels[i];
    if (!isFinite(c) || c.x < 0 || c.y < 0 || c.z < 0)
      throw std::invalid_argument("the environment image has a negative or non-finite pixel (" + std::to_string(i % width_) +
                                  ", " + std::to_string(i / width_) + ")");
    pixels_[i] = c * scale;
  }

  // Pixel i is picked with probability P_i proportional to its luminance times sin(theta) at
  // its centre, then moved by a tent offset of up to one pixel in each axis (header). The
  // density of directions is then the bilinear interpolant of the P_i over 2 pi^2 sin(theta),
  // which follows the bilinear radiance: radiance / pdf stays about constant even across a
  // small bright sun.
  rowCdf_.assign(size_t(height_) + 1, 0.0f);
  columnCdf_.assign(size_t(height_) * (size_t(width_) + 1), 0.0f);
  std::vector<double> rowWeight(size_t(height_), 0.0);
  double total = 0, meanR = 0, meanG = 0, meanB = 0;
  for (int r = 0; r < height_; ++r) {
    const double pixelSolidAngle =
        2 * kPi / width_ * (std::cos(kPi * double(r) / height_) - std::cos(kPi * double(r + 1) / height_));
    const double sinTheta = std::sin(kPi * (double(r) + 0.5) / height_);
    float* cdf = &columnCdf_[size_t(r) * (width_ + 1)];
    double rowSum = 0;
    for (int c = 0; c < width_; ++c) {
      const Color p = pixels_[size_t(r) * width_ + c];
      rowSum += double(luminance(p));
      meanR += p.x * pixelSolidAngle, meanG += p.y * pixelSolidAngle, meanB += p.z * pixelSolidAngle;
    }
    double running = 0;
    for (int c = 0; c < width_; ++c) {
      running += double(luminance(pixels_[size_t(r) * width_ + c]));
      cdf[c + 1] = rowSum > 0 ? float(running / rowSum) : float(c + 1) / float(width_);
    }
    cdf[width_] = 1.0f;
    rowWeight[size_t(r)] = rowSum * sinTheta;
    total += rowWeight[size_t(r)];
  }
  if (!(total > 0)) throw std::invalid_argument("the environment image is black: it emits no light");
  mean_ = Color(float(meanR / (4 * kPi)), float(meanG / (4 * kPi)), float(meanB / (4 * kPi)));
  double running = 0;
  for (int r = 0; r < height_; ++r) {
    running += rowWeight[size_t(r)];
    rowCdf_[size_t(r) + 1] = float(running / total);
  }
  rowCdf_[size_t(height_)] = 1.0f;
  rowBuckets_ = guideBuckets(size_t(height_));
  columnBuckets_ = guideBuckets(size_t(width_));
  rowGuide_.resize(rowBuckets_ + 1);
  buildGuide(rowCdf_.data(), size_t(height_), rowBuckets_, rowGuide_.data());
  columnGuide_.resize(size_t(height_) * (columnBuckets_ + 1));
  for (size_t r = 0; r < size_t(height_); ++r)
    buildGuide(&columnCdf_[r * (size_t(width_) + 1)], size_t(width_), columnBuckets_,
               &columnGuide_[r * (columnBuckets_ + 1)]);
  // P_i in the units of the solid-angle pdf times sin(theta): a density of 1 per unit square
  // of the pixel grid is W H per unit of uv, and d omega = 2 pi^2 sin(theta) du dv.
  const double perPixel = double(width_) * double(height_) / (2 * kPi * kPi);
  weight_.resize(pixels_.size());
  for (int r = 0; r < height_; ++r) {
    const double sinTheta = std::sin(kPi * (double(r) + 0.5) / height_);
    for (int c = 0; c < width_; ++c) {
      const size_t i = size_t(r) * width_ + c;
      weight_[i] = float(double(luminance(pixels_[i])) * sinTheta / total * perPixel);
    }
  }
}

void EnvironmentMap::directionToUv(Vec3 direction, float& u, float& v) const {
  float sinTheta;
  directionToUv(direction, u, v, sinTheta);
}

void EnvironmentMap::directionToUv(Vec3 direction, float& u, float& v, float& sinTheta) const {
  const Vec3 d = normalize(rowTimes(toLocal_, direction));
  u = std::atan2(d.x, -d.z) * (0.5f * kInvPi);
  u -= std::floor(u);
  if (u >= 1.0f) u = 0.0f;
  const float y = std::clamp(d.y, -1.0f, 1.0f);
  v = std::acos(y) * kInvPi;
  sinTheta = std::sqrt(std::max(0.0f, 1 - y * y));
}

EnvironmentMap::Tables EnvironmentMap::tables() const {
  static_assert(sizeof(Color) == 3 * sizeof(float), "a pixel is three packed floats");
  return {width_,
          height_,
          &pixels_[0].x,
          weight_.data(),
          rowCdf_.data(),
          columnCdf_.data(),
          rowGuide_.data(),
          columnGuide_.data(),
          int(rowBuckets_),
          int(columnBuckets_),
          toWorld_,
          toLocal_};
}

Vec3 EnvironmentMap::uvToDirection(float u, float v) const {
  const float phi = 2 * kPi * u, theta = kPi * v;
  const float sinTheta = std::sin(theta);
  return rowTimes(toWorld_, Vec3(sinTheta * std::sin(phi), std::cos(theta), -sinTheta * std::cos(phi)));
}

Color EnvironmentMap::eval(Vec3 direction) const {
  float u, v;
  directionToUv(direction, u, v);
  return evalAtUv(u, v);
}

Color EnvironmentMap::evalAndPdf(Vec3 direction, float& pdfOut) const {
  float u, v, sinTheta;
  directionToUv(direction, u, v, sinTheta);
  const Bilinear b = bilinearAt(u, v);
  pdfOut = pdfAt(b, sinTheta);
  return b.of(pixels_.data(), width_);
}

EnvironmentMap::Bilinear EnvironmentMap::bilinearAt(float u, float v) const {
  // Between pixel centres: columns wrap around, rows clamp at the poles.
  const float x = u * float(width_) - 0.5f, y = v * float(height_) - 0.5f;
  const float fx = std::floor(x), fy = std::floor(y);
  Bilinear b;
  b.tx = x - fx, b.ty = y - fy;
  // u in [0, 1) puts fx in [-1, width - 1]: one wrap at each edge (no integer division).
  b.x0 = int(fx) < 0 ? width_ - 1 : int(fx), b.x1 = b.x0 + 1 == width_ ? 0 : b.x0 + 1;
  b.y0 = std::clamp(int(fy), 0, height_ - 1), b.y1 = std::clamp(int(fy) + 1, 0, height_ - 1);
  return b;
}

Color EnvironmentMap::evalAtUv(float u, float v) const { return bilinearAt(u, v).of(pixels_.data(), width_); }

float EnvironmentMap::pdfAt(const Bilinear& b, float sinTheta) const {
  // At the poles (sin theta = 0) the density in solid angle is unbounded: sampling never
  // needs it there (the poles are a set of measure zero), so it is 0.
  return sinTheta > 0 ? b.of(weight_.data(), width_) / sinTheta : 0.0f;
}

namespace {
// A tent-distributed offset in (-1, 1) from u in [0, 1): density 1 - |t|.
float tentOffset(float u) { return u < 0.5f ? std::sqrt(2 * u) - 1 : 1 - std::sqrt(2 - 2 * u); }
}  // namespace

bool EnvironmentMap::sample(float u1, float u2, Vec3& direction, float& pdfOut, Color* radiance) const {
  float withinRow, withinColumn;
  const size_t r = pickInterval(rowCdf_.data(), size_t(height_), rowGuide_.data(), rowBuckets_, u2, withinRow);
  const size_t c = pickInterval(&columnCdf_[r * (size_t(width_) + 1)], size_t(width_),
                                &columnGuide_[r * (columnBuckets_ + 1)], columnBuckets_, u1, withinColumn);
  // The pixel centre moved by a tent offset in each axis (the positions within the picked
  // intervals are uniform and independent of the pick). Columns wrap; rows reflect at the
  // poles, which makes the density there the bilinear interpolant with rows clamped, as
  // pdf() computes it.
  float x = float(c) + 0.5f + tentOffset(withinColumn), y = float(r) + 0.5f + tentOffset(withinRow);
  if (x < 0) x += float(width_);
  if (x >= float(width_)) x -= float(width_);
  if (y < 0) y = -y;
  if (y > float(height_)) y = 2 * float(height_) - y;
  direction = uvToDirection(std::min(x / float(width_), 0x1.fffffep-1f), std::min(y / float(height_), 1.0f));
  // From the direction, so that sample() and pdf() agree to the bit.
  if (radiance) {
    *radiance = evalAndPdf(direction, pdfOut);
  } else {
    pdfOut = pdf(direction);
  }
  return pdfOut > 0;
}

float EnvironmentMap::pdf(Vec3 direction) const {
  float u, v, sinTheta;
  directionToUv(direction, u, v, sinTheta);
  return pdfAt(bilinearAt(u, v), sinTheta);
}

}  // namespace erpt
