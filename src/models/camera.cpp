#include "models/camera.h"
#include "core/warp.h"

namespace erpt {

namespace {
float fovToTanHalfX(const CameraSettings& s, int width, int height) {
  float t = std::tan(s.fovDegrees * kPi / 360.0f);
  float aspect = float(width) / float(height);
  FovAxis axis = s.fovAxis;
  if (axis == FovAxis::Smaller) axis = width <= height ? FovAxis::X : FovAxis::Y;
  if (axis == FovAxis::Larger) axis = width >= height ? FovAxis::X : FovAxis::Y;
  switch (axis) {
    case FovAxis::Y:
      return t * aspect;
    case FovAxis::Diagonal:
      return t * float(width) / std::sqrt(float(width) * width + float(height) * height);
    default:
      return t;
  }
}
}  // namespace

Camera::Camera(const CameraSettings& s, int width, int height)
    : toWorld_(s.toWorld),
      toCamera_(s.toWorld.inverse()),
      origin_(s.toWorld.point(Vec3(0.0f))),
      tanHalfX_(fovToTanHalfX(s, width, height)),
      aspect_(float(width) / float(height)),
      nearClip_(s.nearClip),
      farClip_(s.farClip),
      apertureRadius_(s.apertureRadius),
      focusDistance_(s.focusDistance),
      right_(normalize(s.toWorld.vector({1, 0, 0}))),
      up_(normalize(s.toWorld.vector({0, 1, 0}))),
      forward_(normalize(s.toWorld.vector({0, 0, 1}))),
      width_(width),
      height_(height) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) rotation_[3 * r + c] = float(toWorld_(r, c));
}

Camera::Ray Camera::generateRay(float filmX, float filmY) const {
  float u = 1.0f - 2.0f * filmX / float(width_);
  float v = (1.0f - 2.0f * filmY / float(height_)) / aspect_;
  Vec3 local = normalize(Vec3(u * tanHalfX_, v * tanHalfX_, 1.0f));
  Ray r;
  r.origin = origin_;
  r.direction = normalize(toWorld_.vector(local));
  r.tnear = nearClip_ / local.z;
  r.tfar = farClip_ / local.z;
  return r;
}

namespace {
// The ray from `origin` towards the point the pinhole ray along `direction` reaches on the
// plane of focus; clip distances along the new direction.
void aimAtFocus(Vec3 pinhole, Vec3 forward, float focusDistance, float nearClip, float farClip, Vec3 origin,
                Vec3& direction, float& tnear, float& tfar) {
  const Vec3 focus = pinhole + direction * (focusDistance / dot(direction, forward));
  direction = normalize(focus - origin);
  const float cosAxis = dot(direction, forward);
  tnear = nearClip / cosAxis;
  tfar = farClip / cosAxis;
}
}  // namespace

Vec3 Camera::lensPoint(float u1, float u2) const {
  if (!hasLens()) return origin_;
  float x, y;
  squareToDisk(u1, u2, x, y);
  return origin_ + right_ * (x * apertureRadius_) + up_ * (y * apertureRadius_);
}

void Camera::throughLens(float u1, float u2, Vec3& origin, Vec3& direction, float& tnear, float& tfar) const {
  float x, y;
  squareToDisk(u1, u2, x, y);
  origin = origin_ + right_ * (x * apertureRadius_) + up_ * (y * apertureRadius_);
  aimAtFocus(origin_, forward_, focusDistance_, nearClip_, farClip_, origin, direction, tnear, tfar);
}

Camera::Ray Camera::generateRayFrom(Vec3 lensPoint, float filmX, float filmY) const {
  return refocus(lensPoint, generateRay(filmX, filmY));
}

Camera::Ray Camera::refocus(Vec3 lensPoint, Ray r) const {
  if (!hasLens()) return r;
  r.origin = lensPoint;
  aimAtFocus(origin_, forward_, focusDistance_, nearClip_, farClip_, lensPoint, r.direction, r.tnear, r.tfar);
  return r;
}

bool Camera::projectFrom(Vec3 lensPoint, Vec3 p, float& filmX, float& filmY) const {
  if (!hasLens()) return project(p, filmX, filmY);
  // Where the ray from the lens point through p meets the plane of focus, seen through the
  // lens centre (every ray through that point of the plane comes from one film position).
  const Vec3 d = p - lensPoint;
  const float along = dot(d, forward_);
  if (!(along > 0)) return false;
  return project(lensPoint + d * (focusDistance_ / along), filmX, filmY);
}

bool Camera::project(Vec3 p, float& filmX, float& filmY) const {
  Vec3 c = toCamera_.point(p);
  if (c.z <= 0) return false;
  float u = c.x / (c.z * tanHalfX_), v = c.y / (c.z * tanHalfX_);
  filmX = 0.5f * (1.0f - u) * float(width_);
  filmY = 0.5f * (1.0f - v * aspect_) * float(height_);
  return true;
}

float Camera::cosToAxis(Vec3 direction) const {
  Vec3 local = normalize(toCamera_.vector(direction));
  return local.z;
}
}  // namespace erpt
