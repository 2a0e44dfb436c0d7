#include <cfloat>

#include "erpt/math.h"

namespace erpt {

Transform Transform::translate(double x, double y, double z) {
  Transform t;
  t(0, 3) = x;
  t(1, 3) = y;
  t(2, 3) = z;
  return t;
}

Transform Transform::scale(double x, double y, double z) {
  Transform t;
  t(0, 0) = x;
  t(1, 1) = y;
  t(2, 2) = z;
  return t;
}

Transform Transform::rotate(double ax, double ay, double az, double degrees) {
  double len = std::sqrt(ax * ax + ay * ay + az * az);
  ax /= len;
  ay /= len;
  az /= len;
  double rad = degrees * 3.14159265358979323846 / 180.0;
  double s = std::sin(rad), c = std::cos(rad), k = 1.0 - c;
  Transform t;
  t(0, 0) = ax * ax * k + c;
  t(0, 1) = ax * ay * k - az * s;
  t(0, 2) = ax * az * k + ay * s;
  t(1, 0) = ay * ax * k + az * s;
  t(1, 1) = ay * ay * k + c;
  t(1, 2) = ay * az * k - ax * s;
  t(2, 0) = az * ax * k - ay * s;
  t(2, 1) = az * ay * k + ax * s;
  t(2, 2) = az * az * k + c;
  return t;
}

Transform Transform::lookAt(Vec3 origin, Vec3 target, Vec3 up) {
  Vec3 dir = normalize(target - origin);
  Vec3 left = normalize(cross(normalize(up), dir));
  Vec3 newUp = cross(dir, left);
  Transform t;
  const Vec3 cols[4] = {left, newUp, dir, origin};
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 3; ++r) t(r, c) = cols[c][r];
  return t;
}

Transform Transform::operator*(const Transform& o) const {
  Transform r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      double s = 0;
      for (int k = 0; k < 4; ++k) s += (*this)(i, k) * o(k, j);
      r(i, j) = s;
    }
  return r;
}

// Gauss-Jordan elimination with partial pivoting; a singular matrix yields non-finite
// entries, which the scene loader reports.
Transform Transform::inverse() const {
  double a[4][8];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      a[i][j] = (*this)(i, j);
      a[i][j + 4] = i == j ? 1.0 : 0.0;
    }
  for (int col = 0; col < 4; ++col) {
    int pivot = col;
    for (int r = col + 1; r < 4; ++r)
      if (std::abs(a[r][col]) > std::abs(a[pivot][col])) pivot = r;
    if (pivot != col)
      for (int j = 0; j < 8; ++j) std::swap(a[col][j], a[pivot][j]);
    double inv = 1.0 / a[col][col];
    for (int j = 0; j < 8; ++j) a[col][j] *= inv;
    for (int r = 0; r < 4; ++r) {
      if (r == col) continue;
      double f = a[r][col];
      for (int j = 0; j < 8; ++j) a[r][j] -= f * a[col][j];
    }
  }
  Transform r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) r(i, j) = a[i][j + 4];
  return r;
}

Vec3 Transform::point(Vec3 p) const {
  double v[3];
  for (int r = 0; r < 3; ++r) v[r] = (*this)(r, 0) * p.x + (*this)(r, 1) * p.y + (*this)(r, 2) * p.z + (*this)(r, 3);
  double w = (*this)(3, 0) * p.x + (*this)(3, 1) * p.y + (*this)(3, 2) * p.z + (*this)(3, 3);
  return {float(v[0] / w), float(v[1] / w), float(v[2] / w)};
}

Vec3 Transform::vector(Vec3 d) const {
  double v[3];
  for (int r = 0; r < 3; ++r) v[r] = (*this)(r, 0) * d.x + (*this)(r, 1) * d.y + (*this)(r, 2) * d.z;
  return {float(v[0]), float(v[1]), float(v[2])};
}

Vec3 Transform::normal(Vec3 n) const {
  Transform inv = inverse();
  double v[3];
  for (int c = 0; c < 3; ++c) v[c] = inv(0, c) * n.x + inv(1, c) * n.y + inv(2, c) * n.z;
  return {float(v[0]), float(v[1]), float(v[2])};
}

bool Transform::isFinite() const {
  for (double v : m)
    if (!std::isfinite(v)) return false;
  return true;
}

double Transform::determinant3x3() const {
  const Transform& t = *this;
  return t(0, 0) * (t(1, 1) * t(2, 2) - t(1, 2) * t(2, 1)) - t(0, 1) * (t(1, 0) * t(2, 2) - t(1, 2) * t(2, 0)) +
         t(0, 2) * (t(1, 0) * t(2, 1) - t(1, 1) * t(2, 0));
}

namespace {
bool fitsInFloat(const Transform& t) {
  for (double v : t.m)
    if (!(std::abs(v) <= double(FLT_MAX))) return false;  // also false for NaN
  return true;
}
}  // namespace

std::string Transform::defect() const {
  if (!fitsInFloat(*this)) return "has an entry that is infinite, NaN or beyond single-precision range (3.4e38)";
  const Transform& t = *this;
  if (t(3, 0) != 0 || t(3, 1) != 0 || t(3, 2) != 0 || t(3, 3) != 1)
    return "is not affine (its bottom row must be 0 0 0 1)";
  // The inverse's linear part maps normals and directions; its translation, used only for a
  // rigid camera, may be large (a tiny scale far from the origin) without harm.
  if (determinant3x3() != 0) {
    Transform linear = t;
    linear(0, 3) = linear(1, 3) = linear(2, 3) = 0;
    if (!fitsInFloat(linear.inverse())) return "is nearly singular (its inverse is beyond single-precision range)";
  }
  return "";
}

}  // namespace erpt
