// PLY and Mitsuba .serialized readers: small files are written to a temporary directory
// (binary ones byte by byte, serialized shapes compressed with zlib: support/mesh_bytes.h) and
// read back.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "scene/mesh_io.h"
#include "support/mesh_bytes.h"

namespace erpt {
namespace {

namespace fs = std::filesystem;

using test::ByteWriter;

class MeshReadersTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::random_device random;
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("erpt_mesh_readers_" + std::string(info->name()) + "_" + std::to_string(random()));
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(dir_, ignored);
  }

  std::string write(const std::string& name, const std::string& contents) {
    std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << contents;
    return path;
  }

  fs::path dir_;
  Warnings warnings_;
};

// Runs `read` and checks that it throws an InputError whose message names `where` and `cause`.
template <class Read>
void expectInputError(Read read, const std::string& where, const std::string& cause) {
  try {
    read();
    FAIL() << "expected an InputError containing '" << cause << "'";
  } catch (const InputError& e) {
    std::string message = e.what();
    EXPECT_NE(message.find(where + ": error: "), std::string::npos) << message;
    EXPECT_NE(message.find(cause), std::string::npos) << message;
  }
}

void expectVec3(Vec3 actual, Vec3 expected) {
  EXPECT_FLOAT_EQ(actual.x, expected.x);
  EXPECT_FLOAT_EQ(actual.y, expected.y);
  EXPECT_FLOAT_EQ(actual.z, expected.z);
}

// ---------------------------------------------------------------------------------------
// PLY

TEST_F(MeshReadersTest, PlyAsciiQuadWithNormalsAndUvs) {
  std::string path = write("quad.ply",
                           "ply\n"
                           "format ascii 1.0\n"
                           "comment written by a test\n"
                           "obj_info nothing to see\n"
                           "element vertex 4\n"
                           "property float x\nproperty float y\nproperty float z\n"
                           "property float nx\nproperty float ny\nproperty float nz\n"
                           "property float u\nproperty float v\n"
                           "element face 1\n"
                           "property list uchar int vertex_indices\n"
                           "end_header\n"
                           "0 0 0 0 0 1 0 0\n"
                           "1 0 0 0 0 1 1 0\n"
                           "1 1 0 0 0 1 1 1\n"
                           "0 1 0 0 0 1 0 1\n"
                           "4 0 1 2 3\n");
  MeshData mesh = readPly(path, warnings_);
  ASSERT_EQ(mesh.positions.size(), 4u);
  expectVec3(mesh.positions[2], {1, 1, 0});
  ASSERT_EQ(mesh.normals.size(), 4u);
  expectVec3(mesh.normals[3], {0, 0, 1});
  EXPECT_EQ(mesh.uvs, (std::vector<float>{0, 0, 1, 0, 1, 1, 0, 1}));
  EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
  EXPECT_TRUE(warnings_.messages.empty());
}

TEST_F(MeshReadersTest, PlyAsciiAlternativeNamesCrlfAndSkippedData) {
  // s/t texture names, vertex_index, CRLF line ends, an unused vertex property, a face
  // property after the index list and an unknown element with a list in between.
  std::string path = write("alt.ply",
                           "ply\r\n"
                           "format ascii 1.0\r\n"
                           "element vertex 3\r\n"
                           "property double x\r\nproperty double y\r\nproperty double z\r\n"
                           "property uchar red\r\n"
                           "property float s\r\nproperty float t\r\n"
                           "element material 2\r\n"
                           "property list uint8 float32 weights\r\n"
                           "property int32 id\r\n"
                           "element face 1\r\n"
                           "property list uchar uint vertex_index\r\n"
                           "property uchar flags\r\n"
                           "end_header\r\n"
                           "0 0 0 255 0.25 0.5\r\n"
                           "+2 0 0 255 0.75 0.5\r\n"
                           "0 -3.5e0 0 255 1 1\r\n"
                           "3 0.5 1.5 2.5 7\r\n"
                           "0 8\r\n"
                           "3 2 1 0 1\r\n");
  MeshData mesh = readPly(path, warnings_);
  ASSERT_EQ(mesh.positions.size(), 3u);
  expectVec3(mesh.positions[1], {2, 0, 0});
  expectVec3(mesh.positions[2], {0, -3.5f, 0});
  EXPECT_TRUE(mesh.normals.empty());
  EXPECT_EQ(mesh.uvs, (std::vector<float>{0.25f, 0.5f, 0.75f, 0.5f, 1, 1}));
  EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{2, 1, 0}));
}

TEST_F(MeshReadersTest, PlyIncompleteNormalsAreIgnoredWithAWarning) {
  std::string path =
      write("partial.ply",
            "ply\nformat ascii 1.0\nelement vertex 3\n"
            "property float x\nproperty float y\nproperty float z\nproperty float nx\n"
            "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
            "0 0 0 1\n1 0 0 1\n0 1 0 1\n3 0 1 2\n");
  MeshData mesh = readPly(path, warnings_);
  EXPECT_TRUE(mesh.normals.empty());
  ASSERT_EQ(warnings_.messages.size(), 1u);
  EXPECT_NE(warnings_.messages[0].find(path + ":3: warning:"), std::string::npos);
}

// An element without properties holds no data, whatever count it claims: skipped at once
// (found by scripts/fuzz.sh: the skip loop stepped through every empty item, 3e10 of them
// took 130 s in the sanitized libFuzzer build; optimised builds may drop the empty loop).
TEST_F(MeshReadersTest, PlyElementWithoutPropertiesAndAHugeCountIsSkippedAtOnce) {
  ByteWriter w;
  w.text("ply\nformat binary_little_endian 1.0\nelement junk 1000000000000000000\nelement vertex 3\n"
         "property float x\nproperty float y\nproperty float z\n"
         "element face 1\nproperty list uchar int vertex_indices\nend_header\n");
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) w.put(v);
  w.put(uint8_t(3)).put(int32_t(0)).put(int32_t(1)).put(int32_t(2));
  const MeshData mesh = readPly(write("junk.ply", w.bytes), warnings_);
  EXPECT_EQ(mesh.positions.size(), 3u);
  EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{0, 1, 2}));
}

// A pentagon and a triangle in binary PLY: float positions, double normals, float uvs,
// uchar and int lists, plus an unknown element holding a list that must be skipped.
std::string binaryPly(bool bigEndian) {
  ByteWriter w;
  w.bigEndian = bigEndian;
  w.text("ply\n")
      .text(bigEndian ? "format binary_big_endian 1.0\n" : "format binary_little_endian 1.0\n")
      .text("comment mixed types\n")
      .text("element vertex 6\n")
      .text("property float x\nproperty float y\nproperty float z\n")
      .text("property double nx\nproperty double ny\nproperty double nz\n")
      .text("property int16 extra\n")
      .text("property float texture_u\nproperty float texture_v\n")
      .text("element edge 2\n")
      .text("property list int uint16 path\nproperty double length\n")
      .text("element face 2\n")
      .text("property list uchar int vertex_indices\n")
      .text("property list uchar float extras\n")
      .text("end_header\n");
  for (int i = 0; i < 6; ++i) {
    w.put(float(i)).put(float(2 * i)).put(-0.5f);
    w.put(0.0).put(1.0).put(double(i) / 8);
    w.put(int16_t(-i));
    w.put(float(i) / 10).put(1.0f - float(i) / 10);
  }
  w.put(int32_t(3)).put(uint16_t(0)).put(uint16_t(1)).put(uint16_t(2)).put(1.5);
  w.put(int32_t(0)).put(2.5);
  w.put(uint8_t(5));
  for (int32_t i : {0, 1, 2, 3, 4}) w.put(i);
  w.put(uint8_t(1)).put(9.0f);
  w.put(uint8_t(3)).put(int32_t(5)).put(int32_t(4)).put(int32_t(0));
  w.put(uint8_t(0));
  return w.bytes;
}

void checkBinaryPly(const MeshData& mesh) {
  ASSERT_EQ(mesh.positions.size(), 6u);
  expectVec3(mesh.positions[5], {5, 10, -0.5f});
  ASSERT_EQ(mesh.normals.size(), 6u);
  expectVec3(mesh.normals[4], {0, 1, 0.5f});
  ASSERT_EQ(mesh.uvs.size(), 12u);
  EXPECT_FLOAT_EQ(mesh.uvs[6], 0.3f);
  EXPECT_FLOAT_EQ(mesh.uvs[7], 0.7f);
  EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 0, 3, 4, 5, 4, 0}));
}

TEST_F(MeshReadersTest, PlyBinaryLittleEndian) {
  MeshData mesh = readPly(write("le.ply", binaryPly(false)), warnings_);
  checkBinaryPly(mesh);
  EXPECT_TRUE(warnings_.messages.empty());
}

TEST_F(MeshReadersTest, PlyBinaryBigEndian) {
  MeshData mesh = readPly(write("be.ply", binaryPly(true)), warnings_);
  checkBinaryPly(mesh);
}

TEST_F(MeshReadersTest, PlyBinaryTruncated) {
  std::string bytes = binaryPly(false);
  std::string path = write("cut.ply", bytes.substr(0, bytes.size() - 3));
  expectInputError([&] { readPly(path, warnings_); }, path, "unexpected end of file");
}

const char* kTriangleHeader = test::kAsciiTrianglePlyHeader;  // the body starts on line 10

TEST_F(MeshReadersTest, PlyAsciiTruncated) {
  std::string path = write("cut.ply", std::string(kTriangleHeader) + "0 0 0\n1 0 0\n0 1\n");
  expectInputError([&] { readPly(path, warnings_); }, path + ":12", "unexpected end of file");
}

TEST_F(MeshReadersTest, PlyAsciiBadNumberNamesItsLine) {
  std::string path =
      write("bad.ply", std::string(kTriangleHeader) + "0 0 0\n1 0x 0\n0 1 0\n3 0 1 2\n");
  expectInputError([&] { readPly(path, warnings_); }, path + ":11", "bad number '0x'");
}

TEST_F(MeshReadersTest, PlyAsciiFractionalIndexIsABadNumber) {
  std::string path =
      write("bad.ply", std::string(kTriangleHeader) + "0 0 0\n1 0 0\n0 1 0\n3 0 1.5 2\n");
  expectInputError([&] { readPly(path, warnings_); }, path + ":13", "bad number '1.5'");
}

TEST_F(MeshReadersTest, PlyIndexOutOfRange) {
  std::string path =
      write("range.ply", std::string(kTriangleHeader) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n");
  expectInputError([&] { readPly(path, warnings_); }, path + ":13", "vertex index 3 out of range");
}

TEST_F(MeshReadersTest, PlyNegativeIndexOutOfRange) {
  std::string path =
      write("neg.ply", std::string(kTriangleHeader) + "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n");
  expectInputError([&] { readPly(path, warnings_); }, path + ":13", "vertex index -1 out of range");
}

TEST_F(MeshReadersTest, PlyFaceWithTwoVertices) {
  std::string path =
      write("two.ply", std::string(kTriangleHeader) + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n");
  expectInputError([&] { readPly(path, warnings_); }, path + ":13", "face with 2 vertices");
}

TEST_F(MeshReadersTest, PlyMissingFile) {
  std::string path = (dir_ / "missing.ply").string();
  expectInputError([&] { readPly(path, warnings_); }, path, "cannot open mesh file");
}

TEST_F(MeshReadersTest, PlyNotAPlyFile) {
  std::string path = write("obj.ply", "v 0 0 0\n");
  expectInputError([&] { readPly(path, warnings_); }, path + ":1", "not a PLY file");
}

TEST_F(MeshReadersTest, PlyUnsupportedFormat) {
  std::string path = write("odd.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n");
  expectInputError([&] { readPly(path, warnings_); }, path + ":2", "unsupported PLY format");
}

TEST_F(MeshReadersTest, PlyHeaderWithoutEnd) {
  std::string path = write("open.ply", "ply\nformat ascii 1.0\nelement vertex 0\n");
  expectInputError([&] { readPly(path, warnings_); }, path + ":3", "unexpected end of file");
}

TEST_F(MeshReadersTest, PlyUnknownPropertyType) {
  std::string path =
      write("type.ply", "ply\nformat ascii 1.0\nelement vertex 0\nproperty half x\nend_header\n");
  expectInputError([&] { readPly(path, warnings_); }, path + ":4", "unknown property type 'half'");
}

// ---------------------------------------------------------------------------------------
// Mitsuba .serialized

using test::kColors;
using test::kFaceNormals;
using test::kFloat32;
using test::kFloat64;
using test::kNormals;
using test::kUvs;
using test::serializeFile;
using test::TestShape;

TestShape floatTriangleWithNormalsAndUvs() {
  TestShape shape;
  shape.flags = kFloat32 | kNormals | kUvs;
  shape.name = "triangle";
  shape.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  shape.normals = {0, 0, 1, 0, 0, 1, 0, 0, 1};
  shape.uvs = {0, 0, 1, 0, 0, 1};
  shape.indices = {0, 1, 2};
  return shape;
}

TestShape doubleQuad() {
  TestShape shape;
  shape.flags = kFloat64;
  shape.name = "quad in double precision";
  shape.positions = {-1, -1, 0.1, 1, -1, 0.1, 1, 1, 0.1, -1, 1, 0.1};
  shape.indices = {0, 1, 2, 0, 2, 3};
  return shape;
}

void checkFloatTriangle(const MeshData& mesh) {
  ASSERT_EQ(mesh.positions.size(), 3u);
  expectVec3(mesh.positions[1], {1, 0, 0});
  ASSERT_EQ(mesh.normals.size(), 3u);
  expectVec3(mesh.normals[2], {0, 0, 1});
  EXPECT_EQ(mesh.uvs, (std::vector<float>{0, 0, 1, 0, 0, 1}));
  EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{0, 1, 2}));
}

void checkDoubleQuad(const MeshData& mesh) {
  ASSERT_EQ(mesh.positions.size(), 4u);
  expectVec3(mesh.positions[2], {1, 1, 0.1f});
  EXPECT_TRUE(mesh.normals.empty());
  EXPECT_TRUE(mesh.uvs.empty());
  EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
}

TEST_F(MeshReadersTest, SerializedVersion4TwoShapes) {
  std::string path =
      write("two.serialized", serializeFile({floatTriangleWithNormalsAndUvs(), doubleQuad()}, 4));
  checkFloatTriangle(readSerialized(path, 0, warnings_));
  checkDoubleQuad(readSerialized(path, 1, warnings_));
  EXPECT_TRUE(warnings_.messages.empty());
}

TEST_F(MeshReadersTest, SerializedVersion3) {
  std::string path =
      write("v3.serialized", serializeFile({doubleQuad(), floatTriangleWithNormalsAndUvs()}, 3));
  checkDoubleQuad(readSerialized(path, 0, warnings_));
  checkFloatTriangle(readSerialized(path, 1, warnings_));
}

// Version 3 files as Mitsuba 0.6 exporters write them: no precision flag, single precision.
TEST_F(MeshReadersTest, SerializedWithoutPrecisionFlagIsSinglePrecision) {
  for (uint16_t version : {uint16_t(3), uint16_t(4)}) {
    TestShape shape = floatTriangleWithNormalsAndUvs();
    shape.flags &= ~uint32_t(kFloat32);
    std::string path = write("noflag.serialized", serializeFile({shape}, version));
    checkFloatTriangle(readSerialized(path, 0, warnings_));
  }
  TestShape both = floatTriangleWithNormalsAndUvs();
  both.flags |= kFloat64;
  std::string path = write("both.serialized", serializeFile({both}, 4));
  expectInputError([&] { readSerialized(path, 0, warnings_); }, path, "both single (0x1000) and double (0x2000)");
}

TEST_F(MeshReadersTest, SerializedFaceNormalsDropVertexNormalsAndColorsAreSkipped) {
  TestShape shape = floatTriangleWithNormalsAndUvs();
  shape.flags |= kFaceNormals | kColors;
  shape.colors = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  std::string path = write("flat.serialized", serializeFile({doubleQuad(), shape}, 4));
  MeshData mesh = readSerialized(path, 1, warnings_);
  EXPECT_TRUE(mesh.normals.empty());
  EXPECT_EQ(mesh.uvs, (std::vector<float>{0, 0, 1, 0, 0, 1}));
  EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{0, 1, 2}));
}

TEST_F(MeshReadersTest, SerializedShapeIndexOutOfRange) {
  std::string path =
      write("two.serialized", serializeFile({floatTriangleWithNormalsAndUvs(), doubleQuad()}, 4));
  expectInputError([&] { readSerialized(path, 2, warnings_); }, path,
                   "shape index 2 out of range (the file has 2 shapes)");
  expectInputError([&] { readSerialized(path, -1, warnings_); }, path, "out of range");
}

TEST_F(MeshReadersTest, SerializedCorruptZlibData) {
  std::string bytes = serializeFile({floatTriangleWithNormalsAndUvs(), doubleQuad()}, 4);
  bytes[4] = '\0';  // the zlib header's first byte (compression method) of shape 0
  std::string path = write("corrupt.serialized", bytes);
  expectInputError([&] { readSerialized(path, 0, warnings_); }, path,
                   "corrupt compressed shape data");
}

TEST_F(MeshReadersTest, SerializedTruncated) {
  std::string bytes = serializeFile({doubleQuad()}, 4);
  std::string path = write("cut.serialized", bytes.substr(0, bytes.size() / 2));
  expectInputError([&] { readSerialized(path, 0, warnings_); }, path,
                   "unexpected end of compressed shape data");
}

TEST_F(MeshReadersTest, SerializedIndexOutOfRange) {
  TestShape shape = doubleQuad();
  shape.indices = {0, 1, 4};
  std::string path = write("range.serialized", serializeFile({shape}, 4));
  expectInputError([&] { readSerialized(path, 0, warnings_); }, path,
                   "vertex index 4 of triangle 0 out of range");
}

TEST_F(MeshReadersTest, SerializedBadMagicAndVersion) {
  std::string bytes = serializeFile({doubleQuad()}, 4);
  std::string badMagic = bytes;
  badMagic[0] = 'x';
  std::string path = write("magic.serialized", badMagic);
  expectInputError([&] { readSerialized(path, 0, warnings_); }, path, "bad magic number");

  std::string badVersion = bytes;
  badVersion[2] = 5;
  path = write("version.serialized", badVersion);
  expectInputError([&] { readSerialized(path, 0, warnings_); }, path,
                   "unsupported serialized mesh version 5");
}

TEST_F(MeshReadersTest, SerializedMissingFile) {
  std::string path = (dir_ / "missing.serialized").string();
  expectInputError([&] { readSerialized(path, 0, warnings_); }, path, "cannot open mesh file");
}

}  // namespace
}  // namespace erpt
