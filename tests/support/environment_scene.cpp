#include "support/environment_scene.h"

#include <cmath>

namespace erpt::test {

RgbImage skyImage(bool withSun) {
  RgbImage img;
  img.width = 64;
  img.height = 32;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const float v = (float(y) + 0.5f) / float(img.height);
      Color c = v < 0.5f ? Color(0.3f, 0.5f, 1.0f) * (1.2f - v) : Color(0.1f, 0.08f, 0.05f);
      if (withSun && std::abs(x - 20) <= 1 && std::abs(y - 8) <= 1) c = Color(200.0f, 180.0f, 150.0f);
      img.pixels.push_back(c);
    }
  return img;
}

namespace {
// The floor (half-side `floorSize`) and glass sphere under `emitter` (an XML element).
std::string glassSceneWith(const std::string& emitter, const std::string& floorSize = "3") {
  return R"(<scene version="3.0.0">
  <sensor type="perspective"><float name="fov" value="45"/>
    <transform name="to_world"><lookat origin="0,2.2,3.2" target="0,0.4,0" up="0,1,0"/></transform>
    <film type="hdrfilm"><integer name="width" value="64"/><integer name="height" value="64"/>
      <rfilter type="box"/></film></sensor>
  <shape type="rectangle"><transform name="to_world"><rotate x="1" angle="-90"/><scale value=")" + floorSize + R"("/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.6, 0.5"/></bsdf></shape>
  <shape type="sphere"><point name="center" value="0, 0.6, 0"/><float name="radius" value="0.5"/>
    <bsdf type="dielectric"><float name="int_ior" value="1.5"/></bsdf></shape>
  )" + emitter + "\n</scene>";
}
}  // namespace

std::string writeEnvmapGlassScene(const TempDir& dir) {
  writeImageAtomic(dir.file("sky.exr"), skyImage());
  return dir.write("scene.xml", glassSceneWith(R"(<emitter type="envmap"><string name="filename" value="sky.exr"/>
    <transform name="to_world"><rotate y="1" angle="30"/></transform></emitter>)"));
}

std::string writeSkyGlassScene(const TempDir& dir) {
  return dir.write("scene.xml", glassSceneWith(R"(<emitter type="sky"><float name="turbidity" value="2.5"/>
    <vector name="sun_direction" x="-0.4" y="0.55" z="-0.45"/><integer name="resolution" value="256"/></emitter>)",
                                               "40"));
}

std::string writeSunskyGlassScene(const TempDir& dir) {
  return dir.write("scene.xml", glassSceneWith(R"(<emitter type="sunsky"><float name="turbidity" value="2.5"/>
    <vector name="sun_direction" x="-0.4" y="0.55" z="-0.45"/><integer name="resolution" value="128"/>
    <float name="sun_radius_scale" value="25"/><float name="sun_scale" value="0.2"/></emitter>)",
                                               "40"));
}

}  // namespace erpt::test
