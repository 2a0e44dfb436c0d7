#include "support/shading_map_scene.h"

#include <cmath>
#include <cstdio>

#include "erpt/image_io.h"

namespace erpt::test {

namespace {

std::string writeTexture(const TempDir& dir, const std::string& name, int width, int height,
                         Color (*texel)(float u, float v, float parameter), float parameter) {
  RgbImage img;
  img.width = width;
  img.height = height;
  img.pixels.resize(size_t(width) * size_t(height));
  // Row 0 is the top (v = 1); texel centres at half-integers.
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      img.pixels[size_t(y) * size_t(width) + size_t(x)] =
          texel((float(x) + 0.5f) / float(width), 1 - (float(y) + 0.5f) / float(height), parameter);
  const std::string path = dir.file(name);
  writeImageAtomic(path, img);
  return path;
}

std::string number(float v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", double(v));
  return text;
}

}  // namespace

std::string writeTiltNormalMap(const TempDir& dir, float tiltDegrees) {
  return writeTexture(dir, "normal.exr", 4, 4, [](float, float, float degrees) {
    const float t = degrees * 3.14159265f / 180;
    return Color(0.5f * std::sin(t) + 0.5f, 0.5f, 0.5f * std::cos(t) + 0.5f);
  }, tiltDegrees);
}

std::string writeRampHeights(const TempDir& dir, float slope) {
  return writeTexture(dir, "ramp.exr", 64, 4, [](float u, float, float s) { return Color(s * u); }, slope);
}

std::string writeMappedPlaneScene(const TempDir& dir, const std::string& wrapper, float albedo, float irradiance) {
  const std::string diffuse = R"(<bsdf type="diffuse"><rgb name="reflectance" value=")" + number(albedo) + R"("/></bsdf>)";
  std::string bsdf = wrapper;
  bsdf.replace(bsdf.find("%s"), 2, diffuse);
  return dir.write("plane.xml", R"(<scene version="3.0.0">
  <sensor type="perspective"><float name="fov" value="30"/>
    <transform name="to_world"><lookat origin="0,0,2" target="0,0,0" up="0,1,0"/></transform>
    <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="16"/>
      <rfilter type="box"/></film></sensor>
  <shape type="rectangle">)" + bsdf + R"(</shape>
  <emitter type="directional"><vector name="direction" x="0" y="0" z="-1"/>
    <rgb name="irradiance" value=")" + number(irradiance) + R"("/></emitter>
</scene>)");
}

std::string writeMappedBoxScene(const TempDir& dir) {
  // Heights 0.04 sin(2 pi 6 u) sin(2 pi 6 v) over the floor's uv square (6 x 6 bumps).
  writeTexture(dir, "bumps.exr", 256, 256, [](float u, float v, float a) {
    return Color(a * std::sin(2 * 3.14159265f * 6 * u) * std::sin(2 * 3.14159265f * 6 * v));
  }, 0.04f);
  writeTiltNormalMap(dir, 35);
  return dir.write("box.xml", R"(<scene version="3.0.0">
  <sensor type="perspective"><float name="fov" value="50"/>
    <transform name="to_world"><lookat origin="0,2.2,3.4" target="0,0.5,0" up="0,1,0"/></transform>
    <film type="hdrfilm"><integer name="width" value="64"/><integer name="height" value="64"/>
      <rfilter type="box"/></film></sensor>
  <shape type="rectangle"><transform name="to_world"><rotate x="1" angle="-90"/><scale value="2"/></transform>
    <bsdf type="bumpmap"><texture type="bitmap" name="heights"><string name="filename" value="bumps.exr"/></texture>
      <bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.6, 0.5"/></bsdf></bsdf></shape>
  <shape type="rectangle"><transform name="to_world"><scale value="2"/><translate y="1" z="-1.2"/></transform>
    <bsdf type="normalmap"><texture type="bitmap" name="normalmap"><string name="filename" value="normal.exr"/>
      <boolean name="raw" value="true"/></texture>
      <bsdf type="diffuse"><rgb name="reflectance" value="0.4, 0.5, 0.7"/></bsdf></bsdf></shape>
  <shape type="sphere"><point name="center" value="0.3, 0.5, 0"/><float name="radius" value="0.5"/>
    <bsdf type="dielectric"/></shape>
  <shape type="rectangle"><transform name="to_world"><rotate x="1" angle="90"/><scale value="0.35"/>
    <translate x="-0.4" y="2.4" z="0.3"/></transform>
    <emitter type="area"><rgb name="radiance" value="25, 23, 20"/></emitter></shape>
</scene>)");
}

}  // namespace erpt::test
