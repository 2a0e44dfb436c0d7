// Scene loading: both Mitsuba dialects, the shared Cornell box, transforms, defaults and -D.
#include <gtest/gtest.h>

#include <filesystem>

#include "erpt/image_io.h"
#include "erpt/scene_loader.h"
#include "support/test_support.h"

namespace erpt {
namespace {

using test::TempDir;

Vec3 vertex(const Scene& s, uint32_t i) { return s.mesh.position(i); }

TEST(Loader, SharedCornellBox) {
  Scene s = loadScene(test::sharedScenesDir() + "/cornell-box/scene.xml");
  EXPECT_EQ(s.mesh.triangleCount(), 36u);
  EXPECT_EQ(s.shapes.size(), 8u);
  ASSERT_EQ(s.emitters.size(), 1u);
  EXPECT_EQ(s.emitters[0].kind, EmitterKind::Area);
  EXPECT_FLOAT_EQ(s.emitters[0].radiance.x, 17.0f);
  EXPECT_FLOAT_EQ(s.emitters[0].radiance.z, 4.0f);
  EXPECT_EQ(s.film.width, 1024);
  EXPECT_EQ(s.film.height, 1024);
  EXPECT_EQ(s.film.filter, FilterKind::Tent);
  EXPECT_EQ(s.integrator.spp, 64);
  EXPECT_EQ(s.integrator.maxDepth, 65);
  EXPECT_FLOAT_EQ(s.camera.fovDegrees, 19.5f);
  EXPECT_TRUE(s.warnings.messages.empty()) << s.warnings.messages.front();
  // The light's triangles face down into the room.
  for (uint32_t t = 0; t < s.mesh.triangleCount(); ++t)
    if (s.mesh.emitter[t] >= 0) {
      EXPECT_LT(normalize(s.mesh.faceNormal(t)).y, -0.99f);
    }
  // Every material of the walls is two-sided diffuse.
  const Material& floor = s.materials[s.mesh.material[s.shapes[0].firstTriangle]];
  EXPECT_EQ(floor.kind, BsdfKind::Diffuse);
  EXPECT_TRUE(floor.twoSided);
  EXPECT_NEAR(floor.reflectance.value.x, 0.725f, 1e-6f);
}

// A -D the scene never declares or uses is a typo the render would silently ignore: refused,
// naming the parameter.
TEST(Loader, DefineTheSceneDoesNotHaveIsRefused) {
  LoadOptions o;
  o.defines = {{"spp", "7"}, {"resz", "32"}};
  try {
    loadScene(test::sharedScenesDir() + "/cornell-box/scene.xml", o);
    FAIL() << "-D resz was accepted";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("-D resz=32: "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("no parameter 'resz'"), std::string::npos) << e.what();
  }
}

TEST(Loader, DefinesOverrideDefaults) {
  LoadOptions o;
  o.defines = {{"spp", "7"}, {"resx", "32"}, {"resy", "16"}};
  Scene s = loadScene(test::sharedScenesDir() + "/cornell-box/scene.xml", o);
  EXPECT_EQ(s.integrator.spp, 7);
  EXPECT_EQ(s.film.width, 32);
  EXPECT_EQ(s.film.height, 16);
}

// The same small scene in the two dialects must load to the same thing.
const char* kScene06 = R"(<?xml version="1.0"?>
<scene version="0.6.0">
  <integrator type="path"><integer name="maxDepth" value="5"/></integrator>
  <sensor type="perspective">
    <float name="fov" value="40"/>
    <string name="fovAxis" value="y"/>
    <float name="nearClip" value="0.5"/>
    <transform name="toWorld"><lookat origin="0,0,5" target="0,0,0" up="0,1,0"/></transform>
    <sampler type="independent"><integer name="sampleCount" value="16"/></sampler>
    <film type="hdrfilm"><integer name="width" value="40"/><integer name="height" value="30"/>
      <rfilter type="box"/></film>
  </sensor>
  <bsdf type="dielectric" id="glass"><float name="intIOR" value="1.33"/></bsdf>
  <shape type="rectangle">
    <transform name="toWorld"><scale x="2" y="3"/><translate x="1"/></transform>
    <ref id="glass"/>
  </shape>
</scene>)";

const char* kScene3 = R"(<scene version="3.0.0">
  <integrator type="path"><integer name="max_depth" value="5"/></integrator>
  <sensor type="perspective">
    <float name="fov" value="40"/>
    <string name="fov_axis" value="y"/>
    <float name="near_clip" value="0.5"/>
    <transform name="to_world"><lookat origin="0,0,5" target="0,0,0" up="0,1,0"/></transform>
    <sampler type="independent"><integer name="sample_count" value="16"/></sampler>
    <film type="hdrfilm"><integer name="width" value="40"/><integer name="height" value="30"/>
      <rfilter type="box"/></film>
  </sensor>
  <bsdf type="dielectric" id="glass"><float name="int_ior" value="1.33"/></bsdf>
  <shape type="rectangle">
    <transform name="to_world"><scale value="2, 3, 1"/><translate value="1 0 0"/></transform>
    <ref id="glass"/>
  </shape>
</scene>)";

TEST(Loader, BothDialectsAgree) {
  TempDir dir;
  for (const char* text : {kScene06, kScene3}) {
    Scene s = loadScene(dir.write("scene.xml", text));
    EXPECT_TRUE(s.warnings.messages.empty()) << s.warnings.messages.front();
    EXPECT_EQ(s.integrator.maxDepth, 5);
    EXPECT_EQ(s.integrator.spp, 16);
    EXPECT_EQ(s.film.width, 40);
    EXPECT_EQ(s.film.filter, FilterKind::Box);
    EXPECT_EQ(s.camera.fovAxis, FovAxis::Y);
    EXPECT_FLOAT_EQ(s.camera.nearClip, 0.5f);
    ASSERT_EQ(s.mesh.triangleCount(), 2u);
    EXPECT_NEAR(s.materials[s.mesh.material[0]].intIOR, 1.33f, 1e-6f);
    // Scale then translate (document order): x in [-1, 3], y in [-3, 3].
    float minX = 1e9f, maxX = -1e9f, maxY = -1e9f;
    for (uint32_t i = 0; i < s.mesh.vertexCount(); ++i) {
      minX = std::min(minX, vertex(s, i).x);
      maxX = std::max(maxX, vertex(s, i).x);
      maxY = std::max(maxY, vertex(s, i).y);
    }
    EXPECT_FLOAT_EQ(minX, -1.0f);
    EXPECT_FLOAT_EQ(maxX, 3.0f);
    EXPECT_FLOAT_EQ(maxY, 3.0f);
    // lookat from +z towards the origin: the camera's +z axis is world -z.
    Vec3 forward = s.camera.toWorld.vector(Vec3(0, 0, 1));
    EXPECT_NEAR(forward.z, -1.0f, 1e-6f);
  }
}

TEST(Loader, TransformsComposeInDocumentOrder) {
  TempDir dir;
  // Rotate 90 degrees about z, then translate by x=+5: the point (1,0,0) goes to (5,1,0).
  std::string xml = R"(<scene version="3.0.0">
    <shape type="obj"><string name="filename" value="tri.obj"/>
      <transform name="to_world"><rotate z="1" angle="90"/><translate x="5"/></transform></shape>
  </scene>)";
  dir.write("tri.obj", "v 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n");
  Scene s = loadScene(dir.write("s.xml", xml));
  ASSERT_EQ(s.mesh.vertexCount(), 3u);
  EXPECT_NEAR(vertex(s, 0).x, 5.0f, 1e-5f);
  EXPECT_NEAR(vertex(s, 0).y, 1.0f, 1e-5f);
  EXPECT_NEAR(vertex(s, 0).z, 0.0f, 1e-5f);
}

TEST(Loader, MatrixIsRowMajor) {
  TempDir dir;
  std::string xml = R"(<scene version="3.0.0">
    <shape type="obj"><string name="filename" value="tri.obj"/>
      <transform name="to_world"><matrix value="1 0 0 10  0 1 0 20  0 0 1 30  0 0 0 1"/></transform></shape>
  </scene>)";
  dir.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  Scene s = loadScene(dir.write("s.xml", xml));
  EXPECT_FLOAT_EQ(vertex(s, 0).x, 10.0f);
  EXPECT_FLOAT_EQ(vertex(s, 0).y, 20.0f);
  EXPECT_FLOAT_EQ(vertex(s, 0).z, 30.0f);
}

TEST(Loader, IncludeDefaultsAndReferences) {
  TempDir dir;
  dir.write("materials.xml", R"(<scene version="3.0.0">
      <bsdf type="roughconductor" id="metal"><string name="material" value="Au"/>
        <float name="alpha" value="$rough"/><string name="distribution" value="ggx"/></bsdf>
    </scene>)");
  std::string xml = R"(<scene version="3.0.0">
    <default name="rough" value="0.25"/>
    <include filename="materials.xml"/>
    <shape type="cube"><ref id="metal"/></shape>
  </scene>)";
  std::string path = dir.write("s.xml", xml);
  Scene s = loadScene(path);
  const Material& m = s.materials[s.mesh.material[0]];
  EXPECT_EQ(m.kind, BsdfKind::RoughConductor);
  EXPECT_EQ(m.distribution, MicrofacetKind::GGX);
  EXPECT_FLOAT_EQ(m.alpha, 0.25f);
  EXPECT_EQ(s.mesh.triangleCount(), 12u);
  LoadOptions o;
  o.defines = {{"rough", "0.5"}};
  EXPECT_FLOAT_EQ(loadScene(path, o).materials[0].alpha, 0.5f);
}

TEST(Loader, UnsupportedPluginWarnsWithLocationAndFallsBack) {
  TempDir dir;
  std::string xml = "<scene version=\"3.0.0\">\n"
                    "  <shape type=\"cube\">\n"
                    "    <bsdf type=\"principled\"/>\n"
                    "  </shape>\n"
                    "  <shape type=\"hair\"/>\n"
                    "  <medium type=\"homogeneous\"/>\n"
                    "</scene>\n";
  std::string path = dir.write("s.xml", xml);
  Scene s = loadScene(path);
  ASSERT_EQ(s.warnings.messages.size(), 3u);
  EXPECT_NE(s.warnings.messages[0].find(path + ":3: warning: bsdf 'principled' is not supported; using diffuse"),
            std::string::npos)
      << s.warnings.messages[0];
  EXPECT_NE(s.warnings.messages[1].find(path + ":5:"), std::string::npos) << s.warnings.messages[1];
  EXPECT_NE(s.warnings.messages[2].find(path + ":6:"), std::string::npos) << s.warnings.messages[2];
  EXPECT_EQ(s.materials[s.mesh.material[0]].kind, BsdfKind::Diffuse);
}

// blendbsdf: two parts by value or by <ref> (in order), a float or texture weight; twosided
// around it makes both parts two-sided; a nested blend is kept; the wrong number of parts or a
// weight outside [0, 1] is an error.
TEST(Loader, BlendBsdfPartsWeightAndTwoSided) {
  TempDir dir;
  const Scene s = loadScene(dir.write("s.xml", R"(<scene version="3.0.0">
    <bsdf type="conductor" id="metal"/>
    <shape type="cube"><bsdf type="twosided"><bsdf type="blendbsdf"><float name="weight" value="0.25"/>
      <bsdf type="diffuse"><rgb name="reflectance" value="0.1, 0.2, 0.3"/></bsdf><ref id="metal"/></bsdf></bsdf></shape>
    <shape type="sphere"><bsdf type="blendbsdf">
      <texture type="checkerboard" name="weight"><rgb name="color0" value="1"/><rgb name="color1" value="0"/></texture>
      <bsdf type="blendbsdf"><bsdf type="dielectric"/><bsdf type="diffuse"/></bsdf><bsdf type="phong"/></bsdf></shape>
  </scene>)"));
  const Material& cube = s.materials[size_t(s.mesh.material[0])];
  ASSERT_EQ(cube.kind, BsdfKind::Blend);
  ASSERT_EQ(cube.blendParts.size(), 2u);
  EXPECT_EQ(cube.blendParts[0].kind, BsdfKind::Diffuse);
  EXPECT_EQ(cube.blendParts[1].kind, BsdfKind::Conductor);
  EXPECT_TRUE(cube.blendParts[0].twoSided && cube.blendParts[1].twoSided);
  const SurfaceColors c = s.surfaceColors(s.mesh.material[0], 0.5f, 0.5f);
  EXPECT_FLOAT_EQ(c.blendWeight, 0.25f);
  EXPECT_FLOAT_EQ(c.parts[0].reflectance.z, 0.3f);
  const Material& sphere = s.materials[size_t(s.spheres.material[0])];
  ASSERT_EQ(sphere.blendParts[0].kind, BsdfKind::Blend);  // the nested blend
  EXPECT_EQ(sphere.blendParts[0].blendParts[0].kind, BsdfKind::Dielectric);
  EXPECT_EQ(sphere.blendParts[0].blendParts[1].kind, BsdfKind::Diffuse);
  EXPECT_GE(sphere.blendWeight.texture, 0);
  EXPECT_TRUE(s.warnings.messages.empty()) << s.warnings.messages.front();
  EXPECT_THROW(loadScene(dir.write("t.xml", R"(<scene version="3.0.0"><shape type="cube">
    <bsdf type="blendbsdf"><bsdf type="diffuse"/></bsdf></shape></scene>)")), InputError);
  const Scene masked = loadScene(dir.write("m.xml", R"(<scene version="3.0.0"><shape type="cube">
    <bsdf type="blendbsdf"><bsdf type="mask"><bsdf type="diffuse"/></bsdf><bsdf type="diffuse"/></bsdf></shape></scene>)"));
  ASSERT_EQ(masked.warnings.messages.size(), 2u);  // the partial opacity, and the ignored mask
  EXPECT_NE(masked.warnings.messages[1].find("inside a blendbsdf is ignored"), std::string::npos);
  // Two smooth dielectrics (two Dirac refractions ERPT could not tell apart): the first, warned.
  const Scene glass = loadScene(dir.write("g.xml", R"(<scene version="3.0.0"><shape type="cube">
    <bsdf type="blendbsdf"><bsdf type="thindielectric"/><bsdf type="dielectric"/></bsdf></shape></scene>)"));
  EXPECT_EQ(glass.materials[size_t(glass.mesh.material[0])].kind, BsdfKind::ThinDielectric);
  ASSERT_EQ(glass.warnings.messages.size(), 1u);
  EXPECT_NE(glass.warnings.messages[0].find("two smooth dielectrics"), std::string::npos);
  EXPECT_THROW(loadScene(dir.write("u.xml", R"(<scene version="3.0.0"><shape type="cube">
    <bsdf type="blendbsdf"><float name="weight" value="1.5"/><bsdf type="diffuse"/><bsdf type="diffuse"/></bsdf>
    </shape></scene>)")), InputError);
}

TEST(Loader, ShapesAndFlipNormals) {
  TempDir dir;
  std::string xml = R"(<scene version="3.0.0">
    <shape type="rectangle"><boolean name="flip_normals" value="true"/></shape>
    <shape type="disk"/>
    <shape type="sphere"><float name="radius" value="2"/><point name="center" value="1, 0, 0"/></shape>
  </scene>)";
  LoadOptions tessellate;  // exact spheres: tests/tracer/exact_sphere_test.cpp
  tessellate.tessellateSpheres = true;
  Scene s = loadScene(dir.write("s.xml", xml), tessellate);
  ASSERT_EQ(s.shapes.size(), 3u);
  EXPECT_LT(normalize(s.mesh.faceNormal(0)).z, -0.999f);  // flipped rectangle faces -z
  EXPECT_GT(normalize(s.mesh.faceNormal(s.shapes[1].firstTriangle)).z, 0.999f);
  // Sphere: every vertex at distance 2 from (1,0,0), face normals point outwards, and the
  // tessellation is fine enough that no facet is visible (edge angle < 1 degree).
  const ShapeInfo& sphere = s.shapes[2];
  EXPECT_GT(sphere.triangleCount, 100000u);
  for (uint32_t t = sphere.firstTriangle; t < sphere.firstTriangle + sphere.triangleCount; t += 97) {
    Vec3 p = s.mesh.position(s.mesh.v0[t]);
    EXPECT_NEAR(length(p - Vec3(1, 0, 0)), 2.0f, 1e-5f);
    EXPECT_GT(dot(s.mesh.faceNormal(t), p - Vec3(1, 0, 0)), 0.0f);
  }
}

// A scene made on Windows or macOS names files in another letter case than they have on disk.
TEST(Loader, FileInOtherLetterCaseIsUsedWithAWarning) {
  TempDir dir;
  std::filesystem::create_directories(dir.path() / "meshes");
  dir.write("meshes/quad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  Scene s = loadScene(dir.write("s.xml", R"(<scene version="3.0.0"><shape type="obj">
      <string name="filename" value="Meshes/Quad.OBJ"/></shape></scene>)"));
  EXPECT_EQ(s.mesh.triangleCount(), 1u);
  ASSERT_EQ(s.warnings.messages.size(), 1u);
  const std::string& w = s.warnings.messages[0];
  EXPECT_NE(w.find("s.xml:2"), std::string::npos) << w;
  EXPECT_NE(w.find("Meshes/Quad.OBJ' not found; using '"), std::string::npos) << w;
  EXPECT_NE(w.find("meshes/quad.obj'"), std::string::npos) << w;
  // No match in any letter case: still the one-line error.
  EXPECT_THROW(loadScene(dir.write("t.xml", R"(<scene version="3.0.0"><shape type="obj">
      <string name="filename" value="meshes/other.obj"/></shape></scene>)")), InputError);
}

// Mitsuba's open cylinder: radius r around the segment p0 -> p1, outward normals, no caps.
TEST(Loader, CylinderIsAnOpenTubeWithOutwardNormals) {
  TempDir dir;
  Scene s = loadScene(dir.write("s.xml", R"(<scene version="3.0.0"><shape type="cylinder">
      <point name="p0" value="1, 0, 0"/><point name="p1" value="1, 2, 0"/><float name="radius" value="0.5"/>
    </shape></scene>)"));
  ASSERT_EQ(s.shapes.size(), 1u);
  EXPECT_EQ(s.mesh.triangleCount(), 2048u);
  for (uint32_t t = 0; t < s.mesh.triangleCount(); t += 7) {
    const Vec3 p = s.mesh.position(s.mesh.v0[t]);
    const Vec3 radial = Vec3(p.x - 1, 0, p.z);
    EXPECT_NEAR(length(radial), 0.5f, 1e-5f);
    EXPECT_GE(p.y, -1e-6f);
    EXPECT_LE(p.y, 2 + 1e-6f);
    EXPECT_GT(dot(normalize(s.mesh.faceNormal(t)), normalize(radial)), 0.99f);
    EXPECT_NEAR(dot(s.mesh.normal(s.mesh.v0[t]), normalize(radial)), 1.0f, 1e-5f);
  }
  EXPECT_THROW(loadScene(dir.write("t.xml", R"(<scene version="3.0.0"><shape type="cylinder">
      <point name="p0" value="1, 0, 0"/><point name="p1" value="1, 0, 0"/></shape></scene>)")), InputError);
}

// A roughness given to a smooth BSDF (scenes written for the rough variants) is ignored with
// one warning that names what is rendered instead.
TEST(Loader, AlphaOnSmoothBsdfsWarnsNamingTheFallback) {
  TempDir dir;
  Scene s = loadScene(dir.write("s.xml", R"(<scene version="3.0.0">
    <shape type="cube"><bsdf type="dielectric"><float name="alpha" value="0.2"/></bsdf></shape>
    <shape type="cube"><bsdf type="conductor"><float name="alpha_u" value="0.2"/><float name="alpha_v" value="0.1"/></bsdf></shape>
  </scene>)"));
  ASSERT_EQ(s.warnings.messages.size(), 2u);
  EXPECT_NE(s.warnings.messages[0].find(":2: warning: 'dielectric' is smooth and ignores 'alpha'; rendered as a smooth "
                                        "dielectric (use 'roughdielectric' for a rough one)"),
            std::string::npos)
      << s.warnings.messages[0];
  EXPECT_NE(s.warnings.messages[1].find("'conductor' is smooth and ignores 'alpha_u'"), std::string::npos)
      << s.warnings.messages[1];
  EXPECT_EQ(s.materials[s.mesh.material[0]].kind, BsdfKind::Dielectric);
}

TEST(Loader, DegenerateTrianglesAreDroppedAndCounted) {
  TempDir dir;
  dir.write("m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\nf 1 1 3\n");
  Scene s = loadScene(dir.write("s.xml", R"(<scene version="3.0.0"><shape type="obj">
      <string name="filename" value="m.obj"/></shape></scene>)"));
  EXPECT_EQ(s.mesh.triangleCount(), 1u);
  EXPECT_EQ(s.droppedDegenerateTriangles, 2u);
  ASSERT_EQ(s.warnings.messages.size(), 1u);
  EXPECT_NE(s.warnings.messages[0].find("dropped 2 degenerate"), std::string::npos);
}

TEST(Loader, SpectraAndSrgbBecomeRgb) {
  TempDir dir;
  Scene s = loadScene(dir.write("s.xml", R"(<scene version="0.6.0">
      <shape type="cube"><bsdf type="diffuse"><spectrum name="reflectance" value="400:0.5, 500:0.5, 600:0.5, 700:0.5"/></bsdf></shape>
      <shape type="cube"><bsdf type="diffuse"><srgb name="reflectance" value="#ffffff"/></bsdf></shape>
      <shape type="cube"><bsdf type="diffuse"><spectrum name="reflectance" value="0.25"/></bsdf></shape>
    </scene>)"));
  // A flat spectrum is grey (up to the missing tails outside 400-700 nm).
  Color flat = s.materials[0].reflectance.value;
  EXPECT_NEAR(flat.x, 0.5f, 0.03f);
  EXPECT_NEAR(flat.y, 0.5f, 0.03f);
  EXPECT_NEAR(flat.z, 0.5f, 0.03f);
  EXPECT_NEAR(s.materials[1].reflectance.value.y, 1.0f, 1e-5f);
  EXPECT_FLOAT_EQ(s.materials[2].reflectance.value.z, 0.25f);
}

TEST(Loader, CheckerboardTextureWithUvScale) {
  TempDir dir;
  Scene s = loadScene(dir.write("s.xml", R"(<scene version="3.0.0">
      <shape type="rectangle"><bsdf type="diffuse">
        <texture type="checkerboard" name="reflectance">
          <rgb name="color0" value="1, 0, 0"/><rgb name="color1" value="0, 0, 1"/>
          <transform name="to_uv"><scale x="2" y="2"/></transform>
        </texture></bsdf></shape>
    </scene>)"));
  ASSERT_EQ(s.textures.size(), 1u);
  int m = s.mesh.material[0];
  // With to_uv scale 2 there are 4x4 checks over the unit square.
  EXPECT_FLOAT_EQ(s.surfaceColors(m, 0.1f, 0.1f).reflectance.x, 1.0f);
  EXPECT_FLOAT_EQ(s.surfaceColors(m, 0.3f, 0.1f).reflectance.z, 1.0f);
  EXPECT_FLOAT_EQ(s.surfaceColors(m, 0.3f, 0.3f).reflectance.x, 1.0f);
}

}  // namespace
}  // namespace erpt

namespace erpt {
namespace {

float srgbDecode(float v) { return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f); }

TEST(Loader, BitmapTextureIsSrgbDecodedAndBilinear) {
  test::TempDir dir;
  // 2x1 PNG of linear 1 and 0.5: writePngAtomic stores them sRGB-encoded in 8 bits, the
  // loader must decode them back to linear.
  RgbImage img;
  img.width = 2;
  img.height = 1;
  img.pixels = {Color(1.0f), Color(0.5f)};
  writePngAtomic(dir.file("tex.png"), img);
  Scene s = loadScene(dir.write("s.xml", R"(<scene version="3.0.0">
      <shape type="rectangle"><bsdf type="diffuse">
        <texture type="bitmap" name="reflectance"><string name="filename" value="tex.png"/></texture>
      </bsdf></shape></scene>)"));
  ASSERT_EQ(s.textures.size(), 1u);
  int m = s.mesh.material[0];
  const float encoded = 1.055f * std::pow(0.5f, 1.0f / 2.4f) - 0.055f;
  const float dark = srgbDecode(std::round(encoded * 255.0f) / 255.0f);
  EXPECT_NEAR(dark, 0.5f, 0.005f);
  // Texel centres at u = 0.25 and 0.75; halfway between them the values blend evenly.
  EXPECT_NEAR(s.surfaceColors(m, 0.25f, 0.5f).reflectance.x, 1.0f, 1e-4f);
  EXPECT_NEAR(s.surfaceColors(m, 0.75f, 0.5f).reflectance.x, dark, 1e-4f);
  EXPECT_NEAR(s.surfaceColors(m, 0.5f, 0.5f).reflectance.x, 0.5f * (1.0f + dark), 1e-4f);
}

}  // namespace
}  // namespace erpt
