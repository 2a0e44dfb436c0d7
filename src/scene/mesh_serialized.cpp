// Mitsuba 0.6 `.serialized` meshes. A file holds several shapes, each a small header
// (uint16 magic 0x041C, uint16 version 3 or 4) followed by a zlib stream with the shape's
// flags, counts and arrays; a dictionary at the end of the file gives each shape's offset.
// Everything is little-endian. The file has no lines: errors name it as a whole (line 0), with
// the byte offset or the triangle at fault, and the scene loader reports them at the XML line
// that names the file (src/scene/referenced_file.h).
#include <zlib.h>

#include <algorithm>
#include <climits>
#include <cstring>
#include <fstream>
#include <iterator>

#include "io/file_util.h"
#include "scene/mesh_io.h"

namespace erpt {

namespace {

constexpr uint16_t kMagic = 0x041C;

enum ShapeFlags : uint32_t {
  kVertexNormals = 0x0001,
  kTexCoords = 0x0002,
  kVertexColors = 0x0008,
  kFaceNormals = 0x0010,
  kSinglePrecision = 0x1000,
  kDoublePrecision = 0x2000,
};

// Decodes an unsigned little-endian integer of `bytes` bytes, whatever the host's byte order.
uint64_t loadLE(const unsigned char* p, size_t bytes) {
  uint64_t v = 0;
  for (size_t i = 0; i < bytes; ++i) v |= uint64_t(p[i]) << (8 * i);
  return v;
}

float loadFloat(const unsigned char* p) {
  uint32_t bits = uint32_t(loadLE(p, 4));
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

double loadDouble(const unsigned char* p) {
  uint64_t bits = loadLE(p, 8);
  double d;
  std::memcpy(&d, &bits, sizeof d);
  return d;
}

// Pulls decompressed bytes out of one shape's zlib stream on demand, so the arrays can be
// sized from the counts in the stream itself.
class Inflater {
 public:
  // `data` starts at byte `fileOffset` of the file.
  Inflater(const unsigned char* data, size_t size, size_t fileOffset, const std::string& path)
      : path_(path), fileOffset_(fileOffset) {
    stream_.next_in = const_cast<unsigned char*>(data);  // zlib's API is not const-correct
    stream_.avail_in = uInt(std::min<size_t>(size, UINT_MAX));
    if (inflateInit(&stream_) != Z_OK) fail("cannot initialise zlib");
  }
  ~Inflater() { inflateEnd(&stream_); }
  Inflater(const Inflater&) = delete;
  Inflater& operator=(const Inflater&) = delete;

  void read(void* out, size_t size) {
    auto* dst = static_cast<unsigned char*>(out);
    while (size > 0) {
      uInt chunk = uInt(std::min<size_t>(size, UINT_MAX));
      stream_.next_out = dst;
      stream_.avail_out = chunk;
      int status = inflate(&stream_, Z_NO_FLUSH);
      size_t produced = chunk - stream_.avail_out;
      dst += produced;
      size -= produced;
      if (size == 0) break;
      if (status == Z_STREAM_END || (status == Z_BUF_ERROR && stream_.avail_in == 0))
        fail("unexpected end of compressed shape data");
      if (status != Z_OK)
        fail(std::string("corrupt compressed shape data (zlib: ") +
             (stream_.msg ? stream_.msg : "error " + std::to_string(status)) + ")");
    }
  }

  uint64_t readUInt(size_t bytes) {
    unsigned char buffer[8];
    read(buffer, bytes);
    return loadLE(buffer, bytes);
  }

  // Reads `count` floating-point values stored with `bytesPerValue` (4 or 8) bytes each.
  std::vector<float> readReals(size_t count, size_t bytesPerValue) {
    std::vector<unsigned char> raw(count * bytesPerValue);
    read(raw.data(), raw.size());
    std::vector<float> values(count);
    for (size_t i = 0; i < count; ++i) {
      const unsigned char* p = &raw[i * bytesPerValue];
      values[i] = bytesPerValue == 4 ? loadFloat(p) : float(loadDouble(p));
    }
    return values;
  }

  std::string readCString() {
    std::string s;
    char c = 0;
    while (read(&c, 1), c != '\0') s += c;
    return s;
  }

 private:
  // At the compressed byte zlib had read up to.
  [[noreturn]] void fail(const std::string& cause) const {
    throw InputError({path_, 0}, cause + " at byte " + std::to_string(fileOffset_ + stream_.total_in));
  }

  z_stream stream_{};
  const std::string& path_;
  size_t fileOffset_;
};

class SerializedFile {
 public:
  explicit SerializedFile(const std::string& path) : path_(path), data_(readWholeFile(path, "mesh file")) {}

  MeshData readShape(int shapeIndex) {
    int version = shapeHeader(0);
    // Like Mitsuba, the first shape is read from the start of the file without consulting
    // the dictionary, so single-shape files stay readable even if their tail is damaged.
    uint64_t offset = shapeIndex == 0 ? 0 : shapeOffset(shapeIndex, version);
    version = shapeHeader(offset);
    size_t start = size_t(offset) + 4;
    Inflater in(bytes() + start, data_.size() - start, start, path_);
    return readMesh(in, version, data_.size() - start);
  }

 private:
  // Checks the magic and version at `offset` and returns the version.
  int shapeHeader(uint64_t offset) const {
    if (offset > data_.size() || data_.size() - offset < 4)
      fail(offset == 0 ? "file too short for a serialized mesh"
                       : "shape offset beyond end of file");
    const unsigned char* p = bytes() + offset;
    const std::string at = " at byte " + std::to_string(offset);
    if (loadLE(p, 2) != kMagic) fail("not a Mitsuba serialized mesh (bad magic number)" + at);
    uint64_t version = loadLE(p + 2, 2);
    if (version != 3 && version != 4)
      fail("unsupported serialized mesh version " + std::to_string(version) + " (expected 3 or 4)" + at);
    return int(version);
  }

  // Looks shape `index` up in the dictionary at the end of the file: its offsets (uint64
  // in version 4, uint32 in version 3) followed by a uint32 shape count.
  uint64_t shapeOffset(int index, int version) const {
    size_t size = data_.size();
    uint64_t count = loadLE(bytes() + size - 4, 4);
    if (index < 0 || uint64_t(index) >= count)
      fail("shape index " + std::to_string(index) + " out of range (the file has " +
           std::to_string(count) + (count == 1 ? " shape)" : " shapes)"));
    size_t entry = version == 4 ? 8 : 4;
    if ((size - 4) / entry < count) fail("corrupt shape dictionary at end of file");
    size_t at = size - 4 - size_t(count - uint64_t(index)) * entry;
    return loadLE(bytes() + at, entry);
  }

  MeshData readMesh(Inflater& in, int version, size_t compressedSize) const {
    uint32_t flags = uint32_t(in.readUInt(4));
    if (version == 4) in.readCString();  // the shape's name; unused
    uint64_t vertexCount = in.readUInt(8), triangleCount = in.readUInt(8);

    // Mitsuba reads doubles exactly when 0x2000 is set; version 3 writers (and some version 4
    // exporters) set no precision flag at all for single-precision data.
    const bool single = flags & kSinglePrecision, dbl = flags & kDoublePrecision;
    if (single && dbl) fail("shape flags give both single (0x1000) and double (0x2000) precision");
    size_t real = dbl ? 8 : 4;
    if (vertexCount > 0xFFFFFFFFull) fail("too many vertices for 32-bit indices");
    checkPlausible(vertexCount, triangleCount, flags, real, compressedSize);

    MeshData mesh;
    size_t n = size_t(vertexCount);
    mesh.positions = toVec3(in.readReals(3 * n, real));
    if (flags & kVertexNormals) {
      std::vector<Vec3> normals = toVec3(in.readReals(3 * n, real));
      // Face normals requested: Mitsuba ignores stored vertex normals then, so do we.
      if (!(flags & kFaceNormals)) mesh.normals = std::move(normals);
    }
    if (flags & kTexCoords) mesh.uvs = in.readReals(2 * n, real);
    if (flags & kVertexColors) in.readReals(3 * n, real);  // colours are not used for rendering
    mesh.indices = readIndices(in, size_t(triangleCount), vertexCount);
    return mesh;
  }

  // Rejects counts that the compressed bytes could not possibly hold (deflate expands at
  // most ~1032:1), so a corrupt header cannot trigger a huge allocation.
  void checkPlausible(uint64_t vertexCount, uint64_t triangleCount, uint32_t flags, size_t real,
                      size_t compressedSize) const {
    uint64_t perVertex = 3;
    if (flags & kVertexNormals) perVertex += 3;
    if (flags & kTexCoords) perVertex += 2;
    if (flags & kVertexColors) perVertex += 3;
    long double needed =
        (long double)vertexCount * perVertex * real + (long double)triangleCount * 12;
    if (needed > (long double)compressedSize * 1100 + 1024)
      fail("shape counts exceed the file's data (corrupt or truncated file)");
  }

  std::vector<uint32_t> readIndices(Inflater& in, size_t triangleCount,
                                    uint64_t vertexCount) const {
    std::vector<unsigned char> raw(triangleCount * 3 * 4);
    in.read(raw.data(), raw.size());
    std::vector<uint32_t> indices(triangleCount * 3);
    for (size_t i = 0; i < indices.size(); ++i) {
      uint64_t index = loadLE(&raw[4 * i], 4);
      if (index >= vertexCount)
        fail("vertex index " + std::to_string(index) + " of triangle " + std::to_string(i / 3) + " out of range (" +
             std::to_string(vertexCount) + " vertices)");
      indices[i] = uint32_t(index);
    }
    return indices;
  }

  static std::vector<Vec3> toVec3(const std::vector<float>& v) {
    std::vector<Vec3> out(v.size() / 3);
    for (size_t i = 0; i < out.size(); ++i) out[i] = {v[3 * i], v[3 * i + 1], v[3 * i + 2]};
    return out;
  }

  const unsigned char* bytes() const {
    return reinterpret_cast<const unsigned char*>(data_.data());
  }
  [[noreturn]] void fail(const std::string& cause) const { throw InputError({path_, 0}, cause); }

  const std::string& path_;
  std::string data_;
};

}  // namespace

MeshData readSerialized(const std::string& path, int shapeIndex, Warnings& /*warnings*/) {
  return SerializedFile(path).readShape(shapeIndex);
}

}  // namespace erpt
