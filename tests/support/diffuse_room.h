// The closed room the vector-kernel tests shade in: a cube of two-sided diffuse walls around
// the origin (half-size 2), which every ray from inside hits, from either side of its faces;
// and a smooth mesh to put in it, whose shading normals differ from its faces'.
#pragma once

namespace erpt::test {

constexpr const char* kDiffuseRoomWalls = R"(
  <shape type="cube">
    <bsdf type="twosided"><bsdf type="diffuse"><rgb name="reflectance" value="0.7 0.5 0.3"/></bsdf></bsdf>
    <transform name="to_world"><scale value="2"/></transform>
  </shape>)";

// An octahedron (radius 0.5) with vertex normals along its radii, as OBJ text.
constexpr const char* kSmoothOctahedronObj = R"(v 0.5 0 0
v -0.5 0 0
v 0 0.5 0
v 0 -0.5 0
v 0 0 0.5
v 0 0 -0.5
vn 1 0 0
vn -1 0 0
vn 0 1 0
vn 0 -1 0
vn 0 0 1
vn 0 0 -1
f 1//1 3//3 5//5
f 3//3 2//2 5//5
f 2//2 4//4 5//5
f 4//4 1//1 5//5
f 3//3 1//1 6//6
f 2//2 3//3 6//6
f 4//4 2//2 6//6
f 1//1 4//4 6//6
)";

}  // namespace erpt::test
