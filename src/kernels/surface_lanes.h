// Surface math of the vector kernels that handle diffuse triangle hits (the path tracer's shade
// packet, BDPT's walk packet): a triangle hit's point and normals (triangleSurfaceAt), and the
// cosine-weighted direction (squareToCosineHemisphere), lane by lane.
#pragma once

#include "erpt/scene.h"
#include "kernels/lane_vec3.h"

namespace erpt {

struct LaneTriangleHit {
  lanes3::V3 position;
  lanes3::V3 ng;       // unit face normal
  lanes3::V3 shading;  // the interpolated vertex normal where `smooth` and it is not zero, else ng
};

// The hit at barycentrics (b1, b2) of each lane's triangle (as triangleSurfaceAt).
LaneTriangleHit triangleHitLanes(const TriangleSoup& mesh, const lanes3::indices& triangle, const lanes3::batch& b1,
                                 const lanes3::batch& b2, const lanes3::mask& smooth);

// squareToCosineHemisphere of warp.h: the concentric disk lifted to the hemisphere.
lanes3::V3 cosineHemisphereLanes(const lanes3::batch& u1, const lanes3::batch& u2);

}  // namespace erpt
