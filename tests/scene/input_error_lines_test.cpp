// Every rejected scene gives exactly one "file:line: error: cause" line, whatever is wrong
// with it: the XML, an OBJ, PLY (ascii or binary) or .serialized mesh it loads, or an image.
// Text files are reported at their own line; binary files (and files that cannot be read at
// all) at the XML line that names them. Each case also names the file and line it expects, so
// a message pointing at the wrong place fails too.
#include <gtest/gtest.h>

#include <limits>
#include <regex>
#include <string>
#include <vector>

#include "erpt/scene_loader.h"
#include "support/mesh_bytes.h"
#include "support/test_support.h"

namespace erpt {
namespace {

using test::ByteWriter;
using test::TempDir;

struct File {
  std::string name, contents;  // a name ending in '/' makes a directory
};

struct RejectCase {
  std::string name;
  std::string sceneXml;  // written to scene.xml
  std::vector<File> files;
  std::string file;   // the file the error must name (in the case's directory)
  int line;           // and its line
  std::string cause;  // expected part of the cause
};

// Readable test names in ctest output instead of a byte dump.
void PrintTo(const RejectCase& c, std::ostream* os) { *os << c.name; }

// A scene whose one shape loads `file`; the filename is on line 3, `extra` on line 4.
std::string meshScene(const std::string& type, const std::string& file, const std::string& extra = "") {
  return "<scene version=\"3.0.0\">\n  <shape type=\"" + type + "\">\n    <string name=\"filename\" value=\"" + file +
         "\"/>\n" + (extra.empty() ? "" : "    " + extra + "\n") + "  </shape>\n</scene>\n";
}

// A scene whose sphere carries `property` on line 3.
std::string sphereWith(const std::string& property) {
  return "<scene version=\"3.0.0\">\n  <shape type=\"sphere\">\n    " + property + "\n  </shape>\n</scene>\n";
}

const char* const kTriangleObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";  // faces start on line 4

const char* const kAsciiPlyHeader = test::kAsciiTrianglePlyHeader;  // the body starts on line 10

// A binary PLY triangle whose face lists `indices` (count first, as uchar; items as int32).
std::string binaryPly(const std::vector<int32_t>& indices, int faces = 1) {
  ByteWriter w;
  w.text("ply\nformat binary_little_endian 1.0\nelement vertex 3\n")
      .text("property float x\nproperty float y\nproperty float z\n")
      .text("element face " + std::to_string(faces) + "\nproperty list uchar int vertex_indices\nend_header\n");
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) w.put(v);
  w.put(uint8_t(indices.size()));
  for (int32_t i : indices) w.put(i);
  return w.bytes;
}

test::TestShape serializedTriangle() {
  test::TestShape shape;
  shape.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  shape.indices = {0, 1, 2};
  return shape;
}

std::string serializedWith(const std::vector<uint32_t>& indices, double x = 0) {
  test::TestShape shape = serializedTriangle();
  shape.indices = indices;
  shape.positions[0] = x;
  return test::serializeFile({shape}, 4);
}

std::vector<RejectCase> rejectCases() {
  const std::string scene = "scene.xml";
  const std::string good = test::serializeFile({serializedTriangle()}, 4);
  std::string corruptZlib = good, badMagic = good;
  corruptZlib[4] = '\0';  // the zlib header's compression method
  badMagic[0] = 'x';
  return {
      // The XML itself: syntax, structure, values, references.
      {"XmlUnclosedElement", "<scene version=\"3.0.0\">\n  <shape type=\"cube\">\n</scene>\n", {}, scene, 3,
       "malformed XML"},
      {"XmlTruncated", "<scene version=\"3.0.0\">\n  <shape type=\"cube\"/>\n  <emitter type=\"po", {}, scene, 3,
       "malformed XML"},
      {"XmlEmptyFile", "", {}, scene, 1, "malformed XML"},
      {"XmlWrongRoot", "<?xml version=\"1.0\"?>\n<scenery version=\"3.0.0\"/>\n", {}, scene, 2, "expected <scene>"},
      {"XmlShapeWithoutType", "<scene version=\"3.0.0\">\n  <shape/>\n</scene>\n", {}, scene, 2,
       "needs the attribute 'type'"},
      {"XmlValueWithoutName", sphereWith("<float value=\"2\"/>"), {}, scene, 3, "needs the attribute 'name'"},
      {"XmlBadNumber", sphereWith("<float name=\"radius\" value=\"1.5x\"/>"), {}, scene, 3, "bad number '1.5x'"},
      {"XmlNanNumber", sphereWith("<float name=\"radius\" value=\"nan\"/>"), {}, scene, 3, "non-finite value"},
      {"XmlNewlineInValue", sphereWith("<float name=\"radius\" value=\"1&#10;2\"/>"), {}, scene, 3, "bad number"},
      {"XmlNegativeRadius", sphereWith("<float name=\"radius\" value=\"-1\"/>"), {}, scene, 3, "must be positive"},
      {"XmlUndefinedParameter", sphereWith("<float name=\"radius\" value=\"$r\"/>"), {}, scene, 3,
       "undefined parameter '$r'"},
      {"XmlUnknownSensor", "<scene version=\"3.0.0\">\n  <sensor type=\"fisheye\"/>\n  <shape type=\"cube\"/>\n</scene>\n",
       {}, scene, 2, "unsupported sensor type 'fisheye'"},
      {"XmlUnknownConductor",
       "<scene version=\"3.0.0\">\n  <shape type=\"cube\">\n    <bsdf type=\"conductor\">\n"
       "      <string name=\"material\" value=\"unobtainium\"/>\n    </bsdf>\n  </shape>\n</scene>\n",
       {}, scene, 4, "unknown conductor material"},
      {"XmlUnknownBsdfReference", "<scene version=\"3.0.0\">\n  <shape type=\"cube\">\n    <ref id=\"none\"/>\n  </shape>\n</scene>\n",
       {}, scene, 3, "unknown BSDF id 'none'"},
      {"XmlUnknownShapegroup",
       "<scene version=\"3.0.0\">\n  <shape type=\"cube\"/>\n  <shape type=\"instance\">\n    <ref id=\"g\"/>\n  </shape>\n"
       "</scene>\n",
       {}, scene, 4, "no shapegroup with id 'g'"},
      {"XmlUnknownTransform",
       "<scene version=\"3.0.0\">\n  <shape type=\"cube\">\n    <transform name=\"to_world\">\n      <shear x=\"1\"/>\n"
       "    </transform>\n  </shape>\n</scene>\n",
       {}, scene, 4, "unknown transform operation <shear>"},
      {"XmlMissingInclude", "<scene version=\"3.0.0\">\n  <include filename=\"nope.xml\"/>\n</scene>\n", {}, scene, 2,
       "not found"},
      {"XmlMalformedInclude", "<scene version=\"3.0.0\">\n  <include filename=\"inc.xml\"/>\n</scene>\n",
       {{"inc.xml", "<scene>\n  <shape type=\"cube\">\n</scene>\n"}}, "inc.xml", 3, "malformed XML"},
      {"XmlIncludeIsADirectory", "<scene version=\"3.0.0\">\n  <include filename=\"inc.xml\"/>\n</scene>\n",
       {{"inc.xml/", ""}}, scene, 2, "is a directory"},
      {"XmlNothingToRender", "<scene version=\"3.0.0\">\n  <integrator type=\"path\"/>\n</scene>\n", {}, scene, 1,
       "no geometry and no emitters"},
      {"XmlMissingMeshFile", meshScene("obj", "nope.obj"), {}, scene, 3, "not found"},
      {"XmlMeshFileIsADirectory", meshScene("obj", "m.obj"), {{"m.obj/", ""}}, scene, 3, "is a directory"},
      {"XmlNewlineInFilename", meshScene("obj", "a&#10;b.obj"), {}, scene, 3, "not found"},
      {"XmlNonFiniteAfterTransform",
       "<scene version=\"3.0.0\">\n  <shape type=\"obj\">\n    <string name=\"filename\" value=\"m.obj\"/>\n"
       "    <transform name=\"to_world\"><scale value=\"1e30\"/></transform>\n  </shape>\n</scene>\n",
       {{"m.obj", "v 0 0 0\nv 1e30 0 0\nv 0 1 0\nf 1 2 3\n"}}, scene, 2, "non-finite vertex position"},

      // OBJ: the line of the statement at fault.
      {"ObjVertexIndexOutOfRange", meshScene("obj", "m.obj"), {{"m.obj", kTriangleObj + std::string("f 1 2 3\nf 1 2 4\n")}},
       "m.obj", 5, "vertex 4"},
      {"ObjRelativeIndexBeforeFirstVertex", meshScene("obj", "m.obj"), {{"m.obj", kTriangleObj + std::string("f -1 -2 -4\n")}},
       "m.obj", 4, "vertex -4"},
      {"ObjNormalIndexOutOfRange", meshScene("obj", "m.obj"),
       {{"m.obj", kTriangleObj + std::string("vn 0 0 1\nf 1//1 2//1 3//7\n")}}, "m.obj", 5, "normal 7"},
      {"ObjUvIndexOutOfRange", meshScene("obj", "m.obj"),
       {{"m.obj", kTriangleObj + std::string("vt 0 0\nf 1/1 2/2 3/1\n")}}, "m.obj", 5, "texture coordinate 2"},
      {"ObjQuadIndexOutOfRange", meshScene("obj", "m.obj"),
       {{"m.obj", kTriangleObj + std::string("v 1 1 0\nf 1 2 3\nf 1 2 4 9\n")}}, "m.obj", 6, "vertex 9"},
      {"ObjIndexOutOfRangeAfterCrLf", meshScene("obj", "m.obj"),
       {{"m.obj", "v 0 0 0\r\nv 1 0 0\r\n# comment\r\nv 0 1 0\r\n\r\nf 1 2 5\r\n"}}, "m.obj", 6, "vertex 5"},
      {"ObjZeroIndex", meshScene("obj", "m.obj"), {{"m.obj", kTriangleObj + std::string("f 1 2 3\nf 0 1 2\n")}}, "m.obj", 5,
       "'0'"},
      {"ObjNonNumericIndex", meshScene("obj", "m.obj"), {{"m.obj", kTriangleObj + std::string("f a b c\n")}}, "m.obj", 4,
       "'a'"},
      {"ObjZeroIndexInPolyline", meshScene("obj", "m.obj"), {{"m.obj", kTriangleObj + std::string("f 1 2 3\nl 0 1\n")}},
       "m.obj", 5, "'0'"},
      {"ObjInfiniteVertex", meshScene("obj", "m.obj"), {{"m.obj", "v 0 0 0\nv 1 0 0\nv 0 1e999 0\nf 1 2 3\n"}}, "m.obj", 3,
       "non-finite vertex position"},

      // ASCII PLY: the line of the value at fault, or of the header line.
      {"PlyAsciiBadNumber", meshScene("ply", "m.ply"), {{"m.ply", kAsciiPlyHeader + std::string("0 0 0\n1 0x 0\n0 1 0\n3 0 1 2\n")}},
       "m.ply", 11, "bad number '0x'"},
      {"PlyAsciiIndexOutOfRange", meshScene("ply", "m.ply"),
       {{"m.ply", kAsciiPlyHeader + std::string("0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n")}}, "m.ply", 13, "vertex index 3"},
      {"PlyAsciiTruncated", meshScene("ply", "m.ply"), {{"m.ply", kAsciiPlyHeader + std::string("0 0 0\n1 0 0\n0 1")}},
       "m.ply", 12, "unexpected end of file"},
      {"PlyAsciiNanVertex", meshScene("ply", "m.ply"),
       {{"m.ply", kAsciiPlyHeader + std::string("0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n")}}, "m.ply", 11,
       "non-finite vertex position"},
      {"PlyEmptyFile", meshScene("ply", "m.ply"), {{"m.ply", ""}}, "m.ply", 1, "not a PLY file"},
      {"PlyUnknownPropertyType", meshScene("ply", "m.ply"),
       {{"m.ply", "ply\nformat ascii 1.0\nelement vertex 0\nproperty half x\nend_header\n"}}, "m.ply", 4,
       "unknown property type 'half'"},
      {"PlyNoVertexElement", meshScene("ply", "m.ply"), {{"m.ply", "ply\nformat ascii 1.0\nend_header\n"}}, "m.ply", 3,
       "no vertex element"},

      // Binary PLY: the header has lines; the body is reported at the XML with a byte offset.
      {"PlyBinaryIndexOutOfRange", meshScene("ply", "m.ply"), {{"m.ply", binaryPly({0, 1, 7})}}, scene, 3,
       "vertex index 7 out of range"},
      {"PlyBinaryNegativeIndex", meshScene("ply", "m.ply"), {{"m.ply", binaryPly({0, -1, 2})}}, scene, 3,
       "vertex index -1 out of range"},
      {"PlyBinaryFaceWithTwoVertices", meshScene("ply", "m.ply"), {{"m.ply", binaryPly({0, 1})}}, scene, 3,
       "face with 2 vertices"},
      {"PlyBinaryTruncated", meshScene("ply", "m.ply"), {{"m.ply", binaryPly({0, 1, 2}, 2)}}, scene, 3,
       "unexpected end of file"},
      {"PlyBinaryBadHeader", meshScene("ply", "m.ply"),
       {{"m.ply", "ply\nformat binary_little_endian 1.0\nelement vertex x\nend_header\n"}}, "m.ply", 3,
       "bad element count 'x'"},

      // .serialized: no lines at all.
      {"SerializedBadMagic", meshScene("serialized", "m.serialized"), {{"m.serialized", badMagic}}, scene, 3,
       "bad magic number"},
      {"SerializedEmptyFile", meshScene("serialized", "m.serialized"), {{"m.serialized", ""}}, scene, 3,
       "file too short"},
      {"SerializedTruncated", meshScene("serialized", "m.serialized"), {{"m.serialized", good.substr(0, good.size() / 2)}},
       scene, 3, "unexpected end of compressed shape data"},
      {"SerializedCorruptZlib", meshScene("serialized", "m.serialized"), {{"m.serialized", corruptZlib}}, scene, 3,
       "corrupt compressed shape data"},
      {"SerializedIndexOutOfRange", meshScene("serialized", "m.serialized"), {{"m.serialized", serializedWith({0, 1, 5})}},
       scene, 3, "vertex index 5 of triangle 0 out of range"},
      {"SerializedShapeIndexOutOfRange",
       meshScene("serialized", "m.serialized", "<integer name=\"shape_index\" value=\"3\"/>"), {{"m.serialized", good}},
       scene, 3, "shape index 3 out of range"},
      {"SerializedNanVertex", meshScene("serialized", "m.serialized"),
       {{"m.serialized", serializedWith({0, 1, 2}, std::numeric_limits<double>::quiet_NaN())}}, scene, 2,
       "non-finite vertex position"},

      // Images: reported at the XML line that names them.
      {"TextureNotAnImage",
       "<scene version=\"3.0.0\">\n  <shape type=\"cube\">\n    <bsdf type=\"diffuse\">\n"
       "      <texture type=\"bitmap\" name=\"reflectance\">\n        <string name=\"filename\" value=\"t.png\"/>\n"
       "      </texture>\n    </bsdf>\n  </shape>\n</scene>\n",
       {{"t.png", "not a png"}}, scene, 5, "cannot read image"},
      {"EnvironmentMapNotAnImage",
       "<scene version=\"3.0.0\">\n  <emitter type=\"envmap\">\n    <string name=\"filename\" value=\"sky.exr\"/>\n"
       "  </emitter>\n</scene>\n",
       {{"sky.exr", "not an exr"}}, scene, 3, "cannot read image"},
      {"EnvironmentMapEmptyFile",
       "<scene version=\"3.0.0\">\n  <emitter type=\"envmap\">\n    <string name=\"filename\" value=\"sky.hdr\"/>\n"
       "  </emitter>\n</scene>\n",
       {{"sky.hdr", ""}}, scene, 3, "cannot read image"},
  };
}

// Writes the case's scene and files into `dir`; returns the scene's path.
std::string writeCase(const RejectCase& c, const TempDir& dir) {
  for (const File& f : c.files) {
    if (!f.name.empty() && f.name.back() == '/')
      std::filesystem::create_directories(dir.file(f.name));
    else
      dir.write(f.name, f.contents);
  }
  return dir.write("scene.xml", c.sceneXml);
}

// The loader's message for the case ("" and a test failure if it loads or throws anything else).
std::string rejection(const std::string& scenePath, int* line = nullptr) {
  try {
    loadScene(scenePath);
  } catch (const InputError& e) {
    if (line) *line = e.where().line;
    return e.what();
  }
  ADD_FAILURE() << "the scene was accepted";
  return "";
}

class InputErrorLines : public ::testing::TestWithParam<RejectCase> {};

TEST_P(InputErrorLines, OneLineNamingFileLineAndCause) {
  const RejectCase& c = GetParam();
  TempDir dir;
  int line = 0;
  const std::string message = rejection(writeCase(c, dir), &line);
  EXPECT_TRUE(std::regex_match(message, std::regex("[^\n\r]+:[0-9]+: error: [^\n\r]+"))) << message;
  EXPECT_GT(line, 0) << message;
  const std::string where = dir.file(c.file) + ":" + std::to_string(c.line) + ": error: ";
  EXPECT_EQ(message.compare(0, where.size(), where), 0) << "expected at " << where << "\n got " << message;
  EXPECT_NE(message.find(c.cause), std::string::npos) << message;
}

// The CLI prints the loader's line and nothing else, for `render` and `info` alike.
TEST_P(InputErrorLines, CliPrintsExactlyThatLine) {
  const RejectCase& c = GetParam();
  TempDir dir;
  const std::string scene = writeCase(c, dir);
  const std::string message = rejection(scene);
  for (const std::string& command :
       {"render -q '" + scene + "' -o '" + dir.file("out.exr") + "' --spp 1", "info '" + scene + "'"}) {
    const test::CommandResult r = test::runCli(command);
    EXPECT_EQ(r.exitCode, 1) << command;
    EXPECT_EQ(r.output, message + "\n") << command;
  }
}

INSTANTIATE_TEST_SUITE_P(Scene, InputErrorLines, ::testing::ValuesIn(rejectCases()),
                         [](const ::testing::TestParamInfo<RejectCase>& info) { return info.param.name; });

}  // namespace
}  // namespace erpt
