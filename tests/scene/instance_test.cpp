// `shapegroup` + `instance`: the same picture as the shapes written out with the composed
// transforms (instances are loaded as copies), and clear errors for bad references.
#include <gtest/gtest.h>

#include "erpt/render.h"
#include "erpt/scene_loader.h"
#include "support/test_support.h"

namespace erpt {
namespace {

const char* kHeader = R"(<scene version="3.0.0">
  <sensor type="perspective"><float name="fov" value="50"/>
    <transform name="to_world"><lookat origin="0,3,6" target="0,0.5,0" up="0,1,0"/></transform>
    <film type="hdrfilm"><integer name="width" value="48"/><integer name="height" value="48"/>
      <rfilter type="box"/></film></sensor>
  <shape type="rectangle"><transform name="to_world"><rotate x="1" angle="-90"/><scale value="4"/></transform></shape>
  <emitter type="constant"><rgb name="radiance" value="1"/></emitter>
  <shape type="sphere"><point name="center" value="0,4,0"/><float name="radius" value="0.5"/>
    <emitter type="area"><rgb name="radiance" value="10"/></emitter></shape>
)";

TEST(Instance, CopiesGiveTheWrittenOutPicture) {
  test::TempDir dir;
  dir.write("tri.obj", "v 0 0 0\nv 0.6 0 0\nv 0 0.9 0.2\nf 1 2 3\n");
  const std::string group = R"(<shape type="obj"><string name="filename" value="tri.obj"/>
        <transform name="to_world"><translate z="0.6"/></transform></shape>
      <shape type="cube"><transform name="to_world"><scale value="0.4"/><translate y="0.4"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.8, 0.2, 0.2"/></bsdf></shape>
      <shape type="sphere"><point name="center" value="0.9, 0.3, 0"/><float name="radius" value="0.3"/>
        <bsdf type="dielectric"/></shape>)";
  const Scene instanced = loadScene(dir.write("a.xml", std::string(kHeader) + R"(
    <shape type="shapegroup" id="thing">)" + group + R"(</shape>
    <shape type="instance"><ref id="thing"/><transform name="to_world"><translate x="-1.2"/></transform></shape>
    <shape type="instance"><ref id="thing"/><transform name="to_world"><rotate y="1" angle="40"/><translate x="1.2" z="-0.5"/></transform></shape>
  </scene>)"));
  // The same shapes, each with the instance's transform after its own (document order).
  const Scene written = loadScene(dir.write("b.xml", std::string(kHeader) + R"(
    <shape type="obj"><string name="filename" value="tri.obj"/>
      <transform name="to_world"><translate z="0.6"/><translate x="-1.2"/></transform></shape>
    <shape type="obj"><string name="filename" value="tri.obj"/>
      <transform name="to_world"><translate z="0.6"/><rotate y="1" angle="40"/><translate x="1.2" z="-0.5"/></transform></shape>
    <shape type="cube"><transform name="to_world"><scale value="0.4"/><translate y="0.4"/><translate x="-1.2"/></transform>
      <bsdf type="diffuse"><rgb name="reflectance" value="0.8, 0.2, 0.2"/></bsdf></shape>
    <shape type="sphere"><point name="center" value="0.9, 0.3, 0"/><float name="radius" value="0.3"/>
      <transform name="to_world"><translate x="-1.2"/></transform><bsdf type="dielectric"/></shape>
    <shape type="cube"><transform name="to_world"><scale value="0.4"/><translate y="0.4"/><rotate y="1" angle="40"/>
      <translate x="1.2" z="-0.5"/></transform><bsdf type="diffuse"><rgb name="reflectance" value="0.8, 0.2, 0.2"/></bsdf></shape>
    <shape type="sphere"><point name="center" value="0.9, 0.3, 0"/><float name="radius" value="0.3"/>
      <transform name="to_world"><rotate y="1" angle="40"/><translate x="1.2" z="-0.5"/></transform><bsdf type="dielectric"/></shape>
  </scene>)"));
  EXPECT_TRUE(instanced.warnings.messages.empty()) << instanced.warnings.messages.front();
  ASSERT_EQ(instanced.mesh.triangleCount(), written.mesh.triangleCount());
  ASSERT_EQ(instanced.spheres.count(), written.spheres.count());
  for (const char* integrator : {"path", "erpt"}) {
    RenderSettings s;
    s.integrator = integrator;
    s.spp = 8;
    s.seed = 5;
    RenderStats sa, sb;
    const RgbImage a = render(instanced, s, sa), b = render(written, s, sb);
    double total = 0, difference = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
      total += luminance(b.pixels[i]);
      difference += std::abs(luminance(a.pixels[i]) - luminance(b.pixels[i]));
    }
    // Bit-identical up to the last digit of the composed transforms (ERPT chains may part
    // ways after such a digit, hence its wider bound).
    EXPECT_LT(difference, (std::string(integrator) == "path" ? 1e-4 : 0.05) * total) << integrator;
  }
}

TEST(Instance, BadReferencesAreInputErrors) {
  test::TempDir dir;
  for (const char* bad : {R"(<shape type="instance"><ref id="none"/></shape>)", R"(<shape type="instance"/>)",
                          R"(<shape type="shapegroup"><shape type="cube"/></shape>)"}) {
    try {
      loadScene(dir.write("c.xml", std::string("<scene version=\"3.0.0\">\n<shape type=\"cube\"/>\n") + bad + "</scene>"));
      ADD_FAILURE() << bad << " loaded";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("c.xml:3"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace erpt
