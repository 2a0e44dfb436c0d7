// The closed room the vector-kernel tests shade in: a cube of two-sided diffuse walls around
// the origin (half-size 2), which every ray from inside hits, from either side of its faces.
#pragma once

namespace erpt::test {

constexpr const char* kDiffuseRoomWalls = R"(
  <shape type="cube">
    <bsdf type="twosided"><bsdf type="diffuse"><rgb name="reflectance" value="0.7 0.5 0.3"/></bsdf></bsdf>
    <transform name="to_world"><scale value="2"/></transform>
  </shape>)";

}  // namespace erpt::test
