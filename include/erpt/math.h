// Small vector math used everywhere: 3-vectors (also RGB colours), orthonormal frames and
// 4x4 affine transforms. Geometry is single precision; transforms are composed in double
// while a scene loads and applied once, so long matrix chains do not lose precision.
#pragma once

#include <algorithm>
#include <array>
#include <string>
#include <cmath>
#include <cstdint>

namespace erpt {

constexpr float kPi = 3.14159265358979323846f;
constexpr float kInvPi = 0.31830988618379067154f;

struct Vec3 {
  float x = 0, y = 0, z = 0;
  constexpr Vec3() = default;
  constexpr Vec3(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
  constexpr explicit Vec3(float s) : x(s), y(s), z(s) {}
  float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  float& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
};

using Color = Vec3;  // linear RGB

inline Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator-(Vec3 a) { return {-a.x, -a.y, -a.z}; }
inline Vec3 operator*(Vec3 a, Vec3 b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
inline Vec3 operator/(Vec3 a, Vec3 b) { return {a.x / b.x, a.y / b.y, a.z / b.z}; }
inline Vec3 operator*(Vec3 a, float s) { return {a.x * s, a.y * s, a.z * s}; }
inline Vec3 operator*(float s, Vec3 a) { return a * s; }
inline Vec3 operator/(Vec3 a, float s) { return a * (1.0f / s); }
inline Vec3& operator+=(Vec3& a, Vec3 b) { return a = a + b; }
inline Vec3& operator*=(Vec3& a, Vec3 b) { return a = a * b; }
inline Vec3& operator*=(Vec3& a, float s) { return a = a * s; }

inline float dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length(Vec3 a) { return std::sqrt(dot(a, a)); }
inline Vec3 normalize(Vec3 a) { return a / length(a); }
inline float maxComponent(Vec3 a) { return std::max(a.x, std::max(a.y, a.z)); }
inline bool isFinite(Vec3 a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }
inline bool isBlack(Color c) { return c.x == 0 && c.y == 0 && c.z == 0; }
// Rec. 709 luminance: the scalar the renderer calls "energy" (ERPT's lum()).
inline float luminance(Color c) { return 0.212671f * c.x + 0.715160f * c.y + 0.072169f * c.z; }
inline Vec3 reflect(Vec3 wi, Vec3 n) { return 2.0f * dot(wi, n) * n - wi; }

// Orthonormal frame around a unit normal (Duff et al. 2017, branchless).
struct Frame {
  Vec3 s, t, n;
  Frame() = default;
  explicit Frame(Vec3 normal) : n(normal) {
    float sign = std::copysign(1.0f, n.z);
    float a = -1.0f / (sign + n.z);
    float b = n.x * n.y * a;
    s = {1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x};
    t = {b, sign + n.y * n.y * a, -n.y};
  }
  // The frame around `normal` whose s is `tangent` (unit, orthogonal to the normal).
  Frame(Vec3 normal, Vec3 tangent) : s(tangent), t(cross(normal, tangent)), n(normal) {}
  Vec3 toLocal(Vec3 v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
  // A frame around `normal` stored as one angle: its s turned by `angle` about the normal from
  // Frame(normal).s (tangentAngle gives the angle of a frame's own s).
  static Frame turned(Vec3 normal, float angle) {
    const Frame f(normal);
    return Frame(normal, f.s * std::cos(angle) + f.t * std::sin(angle));
  }
  float tangentAngle() const {
    const Frame f(n);
    return std::atan2(dot(s, f.t), dot(s, f.s));
  }
  Vec3 toWorld(Vec3 v) const { return s * v.x + t * v.y + n * v.z; }
};

// Row-major 4x4 affine transform (double precision).
struct Transform {
  std::array<double, 16> m{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

  double operator()(int r, int c) const { return m[r * 4 + c]; }
  double& operator()(int r, int c) { return m[r * 4 + c]; }

  static Transform translate(double x, double y, double z);
  static Transform scale(double x, double y, double z);
  static Transform rotate(double axisX, double axisY, double axisZ, double degrees);
  // Mitsuba's lookat: +z towards the target, +y as close to `up` as possible, +x = up x dir.
  static Transform lookAt(Vec3 origin, Vec3 target, Vec3 up);

  Transform operator*(const Transform& o) const;
  Transform inverse() const;
  Vec3 point(Vec3 p) const;
  Vec3 vector(Vec3 v) const;
  // Normals transform by the inverse transpose; the caller normalizes.
  Vec3 normal(Vec3 n) const;
  bool isFinite() const;
  double determinant3x3() const;
  // Why this transform cannot place geometry or a camera in single-precision world space,
  // or "" if it can: every entry finite and within float range, the bottom row affine
  // (0 0 0 1), and, unless the linear part is singular, an inverse (normals, cameras and
  // environment maps use it) whose entries are within float range too. A singular linear part
  // is not a defect here (a zero scale hides a shape, as in Mitsuba); callers that need an
  // inverse check determinant3x3().
  std::string defect() const;
};

}  // namespace erpt
