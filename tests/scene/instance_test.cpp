// `shapegroup` + `instance`: Embree instances of the shareable members (copies of the
// others) give the same picture as the shapes written out with the composed transforms, and
// bad references are clear errors.
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


// Mean |difference| of the two pictures' luminance, relative to the second's mean.
double relativeDifference(const Scene& a, const Scene& b, const char* integrator) {
  RenderSettings s;
  s.integrator = integrator;
  s.spp = 8;
  s.seed = 5;
  RenderStats sa, sb;
  const RgbImage ia = render(a, s, sa), ib = render(b, s, sb);
  double total = 0, difference = 0;
  for (size_t i = 0; i < ia.pixels.size(); ++i) {
    total += luminance(ib.pixels[i]);
    difference += std::abs(luminance(ia.pixels[i]) - luminance(ib.pixels[i]));
  }
  return difference / total;
}

// A smooth-shaded, textured patch (vertex normals tilted apart, uvs across a checkerboard).
const char* kPatchObj =
    "v -0.5 0 -0.5\nv 0.5 0 -0.5\nv 0.5 0.3 0.5\nv -0.5 0 0.5\n"
    "vt 0 0\nvt 3 0\nvt 3 3\nvt 0 3\n"
    "vn -0.3 1 -0.2\nvn 0.4 1 -0.1\nvn 0.2 1 0.3\nvn -0.2 1 0.4\n"
    "f 1/1/1 2/2/2 3/3/3\nf 1/1/1 3/3/3 4/4/4\n";

TEST(Instance, EmbreeInstancesGiveTheWrittenOutPicture) {
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
  // The triangle and the cube are stored once and placed twice; the exact spheres are copies.
  ASSERT_EQ(instanced.instances.count(), 2u);
  ASSERT_EQ(instanced.instances.prototypes.triangleCount(), 13u);
  ASSERT_EQ(instanced.instances.instancedTriangleCount() + instanced.mesh.triangleCount(), written.mesh.triangleCount());
  ASSERT_EQ(instanced.primitiveCount(), written.primitiveCount());
  ASSERT_EQ(instanced.spheres.count(), written.spheres.count());
  // Bit-identical up to the last digit of the composed transforms (ERPT chains may part ways
  // after such a digit, hence its wider bound).
  EXPECT_LT(relativeDifference(instanced, written, "path"), 1e-4);
  EXPECT_LT(relativeDifference(instanced, written, "erpt"), 0.05);
}

// Placements that turn windings (a mirror) and scale unevenly (flat faces only: smooth normals
// under uneven scales are interpolated before the transform, as Mitsuba's instances do, so
// copies differ there); smooth normals and textures in group space; a member that emits (it
// is copied, the rest shared); rough glass with face normals (which side is inside follows
// the winding, which a mirror turns); a directional light and an environment. The cube is
// turned off the axes: an axis-aligned face's normal has zero components whose signs (and
// with them the tangent frames and the noise) differ between the two ways of computing it.
// Two tiny cubes far out fix the scene's bounding box for both scenes: the lights' pick
// weights depend on it, and instances are bounded by their groups' placed boxes
// (conservative), copies by their vertices.
TEST(Instance, MirroredScaledTexturedInstancesUnderADirectionalLight) {
  test::TempDir dir;
  dir.write("patch.obj", kPatchObj);
  const std::string header = R"(<scene version="3.0.0">
  <sensor type="perspective"><float name="fov" value="45"/>
    <transform name="to_world"><lookat origin="0,4,5" target="0,0.3,0" up="0,1,0"/></transform>
    <film type="hdrfilm"><integer name="width" value="40"/><integer name="height" value="40"/>
      <rfilter type="box"/></film></sensor>
  <emitter type="directional"><vector name="direction" value="-0.3,-1,-0.4"/><rgb name="irradiance" value="3"/></emitter>
  <emitter type="constant"><rgb name="radiance" value="0.3"/></emitter>
  <shape type="rectangle"><transform name="to_world"><rotate x="1" angle="-90"/><scale value="4"/><translate y="-0.05"/>
    </transform></shape>
  <shape type="cube"><transform name="to_world"><scale value="0.01"/><translate x="-5" y="-1" z="-5"/></transform></shape>
  <shape type="cube"><transform name="to_world"><scale value="0.01"/><translate x="5" y="4" z="-5"/></transform></shape>
  <bsdf type="diffuse" id="checks"><texture type="checkerboard" name="reflectance">
    <rgb name="color0" value="0.8,0.7,0.2"/><rgb name="color1" value="0.1,0.3,0.6"/></texture></bsdf>
)";
  struct Member {
    std::string open, own;  // the shape up to its transform; its own to_world
    std::string at(const std::string& placement) const {
      return open + "<transform name=\"to_world\">" + own + placement + "</transform></shape>\n";
    }
  };
  const Member patch{R"(<shape type="obj"><string name="filename" value="patch.obj"/><ref id="checks"/>)",
                     R"(<translate x="0.2"/>)"};
  const Member cube{R"(<shape type="cube"><boolean name="face_normals" value="true"/><bsdf type="roughdielectric"><float name="alpha" value="0.2"/></bsdf>)", R"(<scale value="0.3"/><rotate x="0.3" y="1" z="0.2" angle="35"/><translate y="0.3" z="0.8"/>)"};
  const Member lamp{R"(<shape type="rectangle"><emitter type="area"><rgb name="radiance" value="2"/></emitter>)",
                    R"(<scale value="0.2"/><rotate x="1" angle="90"/><translate y="0.3" z="-0.9"/>)"};
  const std::string mirror = R"(<scale x="-1.5" y="1.5" z="1.5"/><rotate y="1" angle="25"/><translate x="-1"/>)";
  const std::string turned = R"(<rotate y="1" angle="-70"/><translate z="-1.5" x="0.3"/>)";
  const std::string uneven = R"(<scale x="1" y="2.5" z="0.6"/><translate x="1.2" z="0.3"/>)";
  auto instance = [](const char* group, const std::string& placement) {
    return std::string("<shape type=\"instance\"><ref id=\"") + group + "\"/><transform name=\"to_world\">" +
           placement + "</transform></shape>\n";
  };
  const Scene instanced = loadScene(dir.write(
      "a.xml", header + "<shape type=\"shapegroup\" id=\"smooth\">" + patch.at("") + cube.at("") + "</shape>\n" +
                   "<shape type=\"shapegroup\" id=\"flat\">" + cube.at("") + lamp.at("") + "</shape>\n" +
                   instance("smooth", mirror) + instance("smooth", turned) + instance("flat", uneven) + "</scene>"));
  const Scene written = loadScene(dir.write("b.xml", header + patch.at(mirror) + cube.at(mirror) + patch.at(turned) +
                                                         cube.at(turned) + cube.at(uneven) + lamp.at(uneven) +
                                                         "</scene>"));
  EXPECT_TRUE(instanced.warnings.messages.empty()) << instanced.warnings.messages.front();
  // Only the lamp (it emits) is a copy: its two triangles, the ground's and the markers are
  // the world mesh.
  ASSERT_EQ(instanced.mesh.triangleCount(), 2u + 2u + 24u);
  ASSERT_EQ(instanced.instances.count(), 3u);
  ASSERT_TRUE(instanced.instances.mirrored[0] && !instanced.instances.mirrored[1]);
  ASSERT_EQ(instanced.primitiveCount(), written.primitiveCount());
  EXPECT_LT(relativeDifference(instanced, written, "path"), 1e-4);
  EXPECT_LT(relativeDifference(instanced, written, "erpt"), 0.05);
}

// Members that need world-space data per triangle or are no meshes are copied per instance:
// masks (the cut-out filter reads world triangles), frames along dp/du (anisotropic
// roughness, normal and bump maps), exact spheres and instances nested in a group.
TEST(Instance, UnshareableMembersAreCopiesAndTheRestIsStoredOnce) {
  test::TempDir dir;
  const Scene scene = loadScene(dir.write("u.xml", std::string(kHeader) + R"(
    <shape type="shapegroup" id="inner"><shape type="cube"/></shape>
    <shape type="shapegroup" id="outer">
      <shape type="rectangle"><bsdf type="mask"><float name="opacity" value="0.5"/><bsdf type="diffuse"/></bsdf></shape>
      <shape type="cube"><bsdf type="roughconductor"><float name="alpha_u" value="0.1"/><float name="alpha_v" value="0.3"/></bsdf></shape>
      <shape type="sphere"><float name="radius" value="0.2"/></shape>
      <shape type="instance"><ref id="inner"/></shape>
      <shape type="cube"><transform name="to_world"><translate x="3"/></transform></shape>
    </shape>
    <shape type="instance"><ref id="outer"/></shape>
    <shape type="instance"><ref id="outer"/><transform name="to_world"><translate z="2"/></transform></shape>
    <shape type="instance"><ref id="outer"/><transform name="to_world"><scale value="0"/></transform></shape>
  </scene>)"));
  // The plain cube is stored once; the ground, the emitting sphere and per instance the masked
  // rectangle, the anisotropic cube, the sphere and the nested cube are in the world.
  EXPECT_EQ(scene.instances.groupCount(), 1u);
  EXPECT_EQ(scene.instances.prototypes.triangleCount(), 12u);
  EXPECT_EQ(scene.instances.count(), 2u);  // the zero-scale one is skipped with a warning
  EXPECT_EQ(scene.mesh.triangleCount(), 2u + 2u * (2u + 12u + 12u));
  EXPECT_EQ(scene.spheres.count(), 1u + 2u);
  // The mask's partial opacity is named once (not once per reading of the member).
  ASSERT_EQ(scene.warnings.messages.size(), 2u);
  EXPECT_NE(scene.warnings.messages[0].find("opacity"), std::string::npos) << scene.warnings.messages[0];
  EXPECT_NE(scene.warnings.messages[1].find("singular"), std::string::npos) << scene.warnings.messages[1];
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
