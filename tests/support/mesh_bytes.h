// Binary mesh files built byte by byte for tests: values in a chosen byte order (binary PLY),
// and Mitsuba .serialized files with zlib-compressed shapes.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

namespace erpt::test {

// The header of an ASCII PLY triangle (3 vertices x y z, 1 face); the body starts on line 10.
inline const char* const kAsciiTrianglePlyHeader =
    "ply\n"
    "format ascii 1.0\n"
    "element vertex 3\n"
    "property float x\nproperty float y\nproperty float z\n"
    "element face 1\n"
    "property list uchar int vertex_indices\n"
    "end_header\n";

// Appends values to a byte string in a chosen byte order, independent of the host's.
struct ByteWriter {
  bool bigEndian = false;
  std::string bytes;

  template <class T>
  ByteWriter& put(T value) {
    static_assert(std::is_arithmetic_v<T>, "numbers only");
    // The value's bits as an unsigned integer of the same size, then shifted out bytewise.
    using Bits = std::conditional_t<
        sizeof(T) == 1, uint8_t,
        std::conditional_t<sizeof(T) == 2, uint16_t,
                           std::conditional_t<sizeof(T) == 4, uint32_t, uint64_t>>>;
    Bits bits;
    std::memcpy(&bits, &value, sizeof bits);
    for (size_t i = 0; i < sizeof(T); ++i) {
      size_t shift = 8 * (bigEndian ? sizeof(T) - 1 - i : i);
      bytes += char((bits >> shift) & 0xFF);
    }
    return *this;
  }
  ByteWriter& text(const std::string& s) {
    bytes += s;
    return *this;
  }
};

// Shape flags of the .serialized format.
enum : uint32_t {
  kNormals = 0x0001,
  kUvs = 0x0002,
  kColors = 0x0008,
  kFaceNormals = 0x0010,
  kFloat32 = 0x1000,
  kFloat64 = 0x2000,
};

struct TestShape {
  uint32_t flags = kFloat32;
  std::string name = "shape";
  std::vector<double> positions, normals, uvs, colors;  // flattened
  std::vector<uint32_t> indices;
};

// One shape as Mitsuba writes it: magic, version, then the zlib-compressed payload.
std::string serializeShape(const TestShape& shape, uint16_t version);
// Shapes followed by the offset dictionary (uint64 offsets in version 4, uint32 in 3).
std::string serializeFile(const std::vector<TestShape>& shapes, uint16_t version);

}  // namespace erpt::test
