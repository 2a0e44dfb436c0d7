// Mitsuba's perspective (pinhole) camera, and its thinlens variant (a lens disk). Camera space: +z looks forward, +y is up and +x
// points to the image's left (Mitsuba's convention); film coordinates are in pixels with
// (0, 0) at the top-left corner of the image.
#pragma once

#include "erpt/scene.h"

namespace erpt {

class Camera {
 public:
  Camera(const CameraSettings& settings, int width, int height);

  struct Ray {
    Vec3 origin, direction;  // direction normalized
    float tnear, tfar;       // the clip planes along this ray
  };
  Ray generateRay(float filmX, float filmY) const;
  // The same for n rays at once (SIMD over the film positions; origins are all position()).
  void generateRays(const float* filmX, const float* filmY, size_t n, float* dirX, float* dirY, float* dirZ,
                    float* tnear, float* tfar) const;
  // World point to film coordinates; false when behind the camera.
  bool project(Vec3 p, float& filmX, float& filmY) const;
  Vec3 position() const { return origin_; }
  // Thin lens (apertureRadius > 0): moves a pinhole ray's origin to the lens point given by
  // (u1, u2) (uniform on the disk) and aims it at the point the pinhole ray reaches on the
  // plane of focus, so everything on that plane stays sharp. Clip distances follow the new
  // direction.
  bool hasLens() const { return apertureRadius_ > 0; }
  // A point on the lens for (u1, u2), uniform on its disk (the pinhole without a lens): where
  // light tracing connects to the camera.
  Vec3 lensPoint(float u1, float u2) const;
  Vec3 forward() const { return forward_; }
  void throughLens(float u1, float u2, Vec3& origin, Vec3& direction, float& tnear, float& tfar) const;
  // The ray from a given lens point through film position (filmX, filmY): the pinhole ray
  // without a lens. ERPT's chains keep their path's lens point (vertex 0) and move the film
  // position: for a fixed lens point the film-to-solid-angle Jacobian is cos^3 / (plane
  // distance)^2 of the ray's own angle to the axis, as for a pinhole (docs/erpt-acceptance.md).
  Ray generateRayFrom(Vec3 lensPoint, float filmX, float filmY) const;
  // The same from the pinhole ray through that film position (generateRay's or
  // generateRays'): without a lens, that ray.
  Ray refocus(Vec3 lensPoint, Ray pinhole) const;
  // The film position whose ray from lensPoint passes through world point p; false behind
  // the lens. project(p) without a lens.
  bool projectFrom(Vec3 lensPoint, Vec3 p, float& filmX, float& filmY) const;
  // Cosine between a world direction leaving the camera and the optical axis.
  float cosToAxis(Vec3 direction) const;
  float tanHalfFovX() const { return tanHalfX_; }
  // Film pixels per unit length on the image plane at distance 1 (square pixels).
  float pixelsPerPlaneUnit() const { return float(width_) / (2 * tanHalfX_); }

 private:
  Transform toWorld_, toCamera_;
  Vec3 origin_;
  float tanHalfX_, aspect_, nearClip_, farClip_;
  float apertureRadius_, focusDistance_;
  Vec3 right_, up_, forward_;  // the camera frame in the world (unit vectors)
  float rotation_[9];  // toWorld_'s 3x3 part in single precision, row-major, for the SIMD path
  int width_, height_;
};

}  // namespace erpt
