#include "support/mask_scene.h"

namespace erpt::test {

std::string writeCheckerMaskScene(const TempDir& dir, bool cutGeometry) {
  // The rectangle spans [-1, 1]^2 with u, v in [0, 1]; a checkerboard scaled 2x in uv has 4x4
  // checks of 0.5 x 0.5, colour0 (opaque) where the check indices sum to an even number.
  std::string obj;
  int vertices = 0;
  for (int iu = 0; iu < 4; ++iu)
    for (int iv = 0; iv < 4; ++iv) {
      if ((iu + iv) % 2 != 0) continue;
      const float x0 = -1 + 0.5f * iu, x1 = x0 + 0.5f, y0 = -1 + 0.5f * iv, y1 = y0 + 0.5f;
      for (auto [x, y] : {std::pair{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}})
        obj += "v " + std::to_string(x) + " " + std::to_string(y) + " 0\n";
      obj += "f " + std::to_string(vertices + 1) + " " + std::to_string(vertices + 2) + " " + std::to_string(vertices + 3) +
             " " + std::to_string(vertices + 4) + "\n";
      vertices += 4;
    }
  dir.write("squares.obj", obj);
  const std::string place = R"(<transform name="to_world"><rotate x="1" angle="-90"/><translate y="1"/></transform>)";
  const std::string plane =
      cutGeometry ? R"(<shape type="obj"><string name="filename" value="squares.obj"/>)" + place +
                        R"(<bsdf type="diffuse"><rgb name="reflectance" value="0.8, 0.3, 0.2"/></bsdf></shape>)"
                  : R"(<shape type="rectangle">)" + place + R"(
        <bsdf type="mask"><texture type="checkerboard" name="opacity"><rgb name="color0" value="1"/>
          <rgb name="color1" value="0"/><transform name="to_uv"><scale value="2"/></transform></texture>
          <bsdf type="diffuse"><rgb name="reflectance" value="0.8, 0.3, 0.2"/></bsdf></bsdf></shape>)";
  return dir.write("scene.xml", R"(<scene version="3.0.0">
  <sensor type="perspective"><float name="fov" value="50"/>
    <transform name="to_world"><lookat origin="0.7,4,2.5" target="0,0.5,0" up="0,1,0"/></transform>
    <film type="hdrfilm"><integer name="width" value="64"/><integer name="height" value="64"/>
      <rfilter type="box"/></film></sensor>
  <shape type="rectangle"><transform name="to_world"><rotate x="1" angle="-90"/><scale value="3"/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.6, 0.6, 0.6"/></bsdf></shape>
  )" + plane + R"(
  <shape type="rectangle"><transform name="to_world"><rotate x="1" angle="90"/><scale value="0.4"/><translate x="0.3" y="3"/></transform>
    <emitter type="area"><rgb name="radiance" value="30"/></emitter></shape>
  <emitter type="constant"><rgb name="radiance" value="0.3"/></emitter>
</scene>)");
}

}  // namespace erpt::test
