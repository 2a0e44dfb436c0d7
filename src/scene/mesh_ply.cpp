// Stanford PLY reader (ascii, binary_little_endian, binary_big_endian), written by hand
// because no PLY library is available. The whole file is read into memory once; the header
// is parsed into element/property declarations and the body is then walked element by
// element, keeping vertex positions/normals/uvs and face index lists and skipping the rest.
// Errors name their line in the header and in an ascii body. A binary body has no lines: its
// errors give the byte offset, at line 0, and the scene loader reports them at the XML line
// that names the file (src/scene/referenced_file.h).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

#include "io/file_util.h"
#include "scene/mesh_io.h"

namespace erpt {

namespace {

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };
enum class PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::Float32;  // the value type, or the item type of a list
  bool isList = false;
  PlyType countType = PlyType::UInt8;  // lists only
};

struct PlyElement {
  std::string name;
  uint64_t count = 0;
  std::vector<PlyProperty> properties;
  int line = 0;  // header line that declares it
};

struct PlyHeader {
  PlyFormat format = PlyFormat::Ascii;
  std::vector<PlyElement> elements;
  size_t bodyOffset = 0;  // first byte after the end_header line
  int lineCount = 0;      // ascii body line numbers continue from here
};

std::vector<std::string> splitWords(const std::string& line) {
  std::istringstream in(line);
  return {std::istream_iterator<std::string>(in), std::istream_iterator<std::string>()};
}

bool parseType(const std::string& name, PlyType& type) {
  static const struct {
    const char* name;
    PlyType type;
  } kNames[] = {
      {"char", PlyType::Int8},       {"int8", PlyType::Int8},       {"uchar", PlyType::UInt8},
      {"uint8", PlyType::UInt8},     {"short", PlyType::Int16},     {"int16", PlyType::Int16},
      {"ushort", PlyType::UInt16},   {"uint16", PlyType::UInt16},   {"int", PlyType::Int32},
      {"int32", PlyType::Int32},     {"uint", PlyType::UInt32},     {"uint32", PlyType::UInt32},
      {"float", PlyType::Float32},   {"float32", PlyType::Float32}, {"double", PlyType::Float64},
      {"float64", PlyType::Float64},
  };
  for (const auto& entry : kNames)
    if (name == entry.name) {
      type = entry.type;
      return true;
    }
  return false;
}

bool isIntegerType(PlyType t) { return t != PlyType::Float32 && t != PlyType::Float64; }

size_t typeSize(PlyType t) {
  switch (t) {
    case PlyType::Int8:
    case PlyType::UInt8:
      return 1;
    case PlyType::Int16:
    case PlyType::UInt16:
      return 2;
    case PlyType::Int32:
    case PlyType::UInt32:
    case PlyType::Float32:
      return 4;
    case PlyType::Float64:
      return 8;
  }
  return 0;
}

// ---------------------------------------------------------------------------------------
// Header

class HeaderParser {
 public:
  HeaderParser(const std::string& data, const std::string& path, Warnings& warnings)
      : data_(data), path_(path), warnings_(warnings) {}

  PlyHeader parse() {
    std::string line;
    if (!nextLine(line) || splitWords(line) != std::vector<std::string>{"ply"})
      fail("not a PLY file (missing 'ply' magic line)");
    while (true) {
      if (!nextLine(line)) fail("unexpected end of file (no end_header line)");
      std::vector<std::string> words = splitWords(line);
      if (words.empty()) continue;
      const std::string& keyword = words[0];
      if (keyword == "end_header") break;
      if (keyword == "format")
        parseFormat(words);
      else if (keyword == "element")
        parseElement(words);
      else if (keyword == "property")
        parseProperty(words);
      else if (keyword != "comment" && keyword != "obj_info")
        warnings_.add(where(), "unknown PLY header line '" + keyword + "' ignored");
    }
    if (!sawFormat_) fail("missing format line in PLY header");
    header_.bodyOffset = pos_;
    header_.lineCount = line_;
    return header_;
  }

 private:
  // Reads the next line without its terminator ("\n" or "\r\n"); false at end of data.
  bool nextLine(std::string& line) {
    if (pos_ >= data_.size()) return false;
    size_t end = data_.find('\n', pos_);
    if (end == std::string::npos) {
      // A header must end with a newline; a last unterminated line cannot be end_header.
      line_++;
      pos_ = data_.size();
      return false;
    }
    line.assign(data_, pos_, end - pos_);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    pos_ = end + 1;
    line_++;
    return true;
  }

  void parseFormat(const std::vector<std::string>& words) {
    if (words.size() < 2) fail("malformed format line");
    if (words[1] == "ascii")
      header_.format = PlyFormat::Ascii;
    else if (words[1] == "binary_little_endian")
      header_.format = PlyFormat::BinaryLittleEndian;
    else if (words[1] == "binary_big_endian")
      header_.format = PlyFormat::BinaryBigEndian;
    else
      fail("unsupported PLY format '" + words[1] + "'");
    sawFormat_ = true;
  }

  void parseElement(const std::vector<std::string>& words) {
    if (words.size() != 3) fail("malformed element line (expected 'element <name> <count>')");
    PlyElement element;
    element.name = words[1];
    element.line = line_;
    const std::string& count = words[2];
    auto result = std::from_chars(count.data(), count.data() + count.size(), element.count);
    if (result.ec != std::errc() || result.ptr != count.data() + count.size())
      fail("bad element count '" + count + "'");
    header_.elements.push_back(std::move(element));
  }

  void parseProperty(const std::vector<std::string>& words) {
    if (header_.elements.empty()) fail("property declared before any element");
    PlyProperty property;
    if (words.size() >= 2 && words[1] == "list") {
      if (words.size() != 5)
        fail("malformed list property (expected 'property list <count type> <item type> <name>')");
      property.isList = true;
      property.countType = typeNamed(words[2]);
      if (!isIntegerType(property.countType)) fail("list count type must be an integer type");
      property.type = typeNamed(words[3]);
      property.name = words[4];
    } else {
      if (words.size() != 3) fail("malformed property line (expected 'property <type> <name>')");
      property.type = typeNamed(words[1]);
      property.name = words[2];
    }
    header_.elements.back().properties.push_back(std::move(property));
  }

  PlyType typeNamed(const std::string& name) {
    PlyType type;
    if (!parseType(name, type)) fail("unknown property type '" + name + "'");
    return type;
  }

  // Line 1 also for an empty file, which has no line at all.
  SourceLocation where() const { return {path_, std::max(line_, 1)}; }
  [[noreturn]] void fail(const std::string& cause) const { throw InputError(where(), cause); }

  const std::string& data_;
  const std::string& path_;
  Warnings& warnings_;
  PlyHeader header_;
  size_t pos_ = 0;
  int line_ = 0;
  bool sawFormat_ = false;
};

// ---------------------------------------------------------------------------------------
// Body sources: both hand out one value at a time as a double, which holds every PLY type
// exactly, so the element walkers below are written once for both encodings.

class AsciiSource {
 public:
  AsciiSource(const std::string& data, const PlyHeader& header, const std::string& path)
      : p_(data.data() + header.bodyOffset),
        end_(data.data() + data.size()),
        path_(path),
        line_(header.lineCount + 1),
        tokenLine_(header.lineCount) {}

  double next(PlyType type) {
    const char* begin = nextToken();
    const char* stop = p_;
    double value = 0;
    std::from_chars_result result;
    if (isIntegerType(type)) {
      long long integer = 0;
      result = std::from_chars(begin, stop, integer);
      value = double(integer);
    } else {
      // from_chars rejects a leading '+', which some writers emit.
      const char* digits = (*begin == '+' && stop - begin > 1) ? begin + 1 : begin;
      result = std::from_chars(digits, stop, value);
    }
    if (result.ec != std::errc() || result.ptr != stop) fail("bad number '" + std::string(begin, stop) + "'");
    return value;
  }

  // At the line of the last value read.
  [[noreturn]] void fail(const std::string& cause) const { throw InputError({path_, tokenLine_}, cause); }
  size_t bytesLeft() const { return size_t(end_ - p_); }

 private:
  // Moves past the next whitespace-separated token and returns its start (p_ is its end).
  const char* nextToken() {
    while (p_ < end_ && isSpace(*p_)) {
      if (*p_ == '\n') line_++;
      p_++;
    }
    if (p_ == end_) fail("unexpected end of file");
    tokenLine_ = line_;
    const char* begin = p_;
    while (p_ < end_ && !isSpace(*p_)) p_++;
    return begin;
  }

  static bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

  const char* p_;
  const char* end_;
  const std::string& path_;
  int line_;       // line of the read position
  int tokenLine_;  // line of the last token read (errors point here)
};

class BinarySource {
 public:
  BinarySource(const std::string& data, const PlyHeader& header, const std::string& path)
      : begin_(reinterpret_cast<const unsigned char*>(data.data())),
        p_(begin_ + header.bodyOffset),
        value_(p_),
        end_(begin_ + data.size()),
        path_(path),
        bigEndian_(header.format == PlyFormat::BinaryBigEndian) {}

  double next(PlyType type) {
    size_t n = typeSize(type);
    value_ = p_;
    if (size_t(end_ - p_) < n) fail("unexpected end of file");
    // Assemble the value's bits arithmetically so the host's byte order does not matter.
    uint64_t bits = 0;
    for (size_t i = 0; i < n; ++i) bits |= uint64_t(p_[bigEndian_ ? n - 1 - i : i]) << (8 * i);
    p_ += n;
    switch (type) {
      case PlyType::Int8:
        return int8_t(uint8_t(bits));
      case PlyType::UInt8:
        return uint8_t(bits);
      case PlyType::Int16:
        return int16_t(uint16_t(bits));
      case PlyType::UInt16:
        return uint16_t(bits);
      case PlyType::Int32:
        return int32_t(uint32_t(bits));
      case PlyType::UInt32:
        return uint32_t(bits);
      case PlyType::Float32: {
        uint32_t u = uint32_t(bits);
        float f;
        std::memcpy(&f, &u, sizeof f);
        return f;
      }
      case PlyType::Float64: {
        double d;
        std::memcpy(&d, &bits, sizeof d);
        return d;
      }
    }
    return 0;
  }

  // At the byte offset of the last value read (no line: see the top of this file).
  [[noreturn]] void fail(const std::string& cause) const {
    throw InputError({path_, 0}, cause + " at byte " + std::to_string(value_ - begin_));
  }
  size_t bytesLeft() const { return size_t(end_ - p_); }

 private:
  const unsigned char* begin_;
  const unsigned char* p_;
  const unsigned char* value_;  // start of the last value read
  const unsigned char* end_;
  const std::string& path_;
  bool bigEndian_;
};

// ---------------------------------------------------------------------------------------
// Elements

// Where each vertex property goes; properties we do not use map to kIgnore.
enum VertexSlot { kX, kY, kZ, kNX, kNY, kNZ, kU, kV, kSlotCount, kIgnore = -1 };

int vertexSlot(const std::string& name) {
  static const struct {
    const char* name;
    VertexSlot slot;
  } kNames[] = {
      {"x", kX},         {"y", kY},         {"z", kZ},         {"nx", kNX},       {"ny", kNY},
      {"nz", kNZ},       {"u", kU},         {"v", kV},         {"s", kU},         {"t", kV},
      {"texture_u", kU}, {"texture_v", kV}, {"texture_s", kU}, {"texture_t", kV},
  };
  for (const auto& entry : kNames)
    if (name == entry.name) return entry.slot;
  return kIgnore;
}

// Reads and drops one property value (all items of a list).
template <class Source>
void skipProperty(Source& src, const PlyProperty& property) {
  if (!property.isList) {
    src.next(property.type);
    return;
  }
  double count = src.next(property.countType);
  if (count < 0) src.fail("negative list length");
  for (uint64_t i = 0, n = uint64_t(count); i < n; ++i) src.next(property.type);
}

template <class Source>
void skipElement(Source& src, const PlyElement& element) {
  // An element without properties holds no data, whatever its count (a huge count would
  // otherwise spin here; found by tests/fuzz).
  if (element.properties.empty()) return;
  for (uint64_t i = 0; i < element.count; ++i)
    for (const PlyProperty& property : element.properties) skipProperty(src, property);
}

struct VertexLayout {
  std::vector<int> slots;  // one per property
  bool hasNormals = false, hasUvs = false;
};

VertexLayout vertexLayout(const PlyElement& element, const std::string& path, Warnings& warnings) {
  VertexLayout layout;
  bool present[kSlotCount] = {};
  for (const PlyProperty& property : element.properties) {
    int slot = property.isList ? kIgnore : vertexSlot(property.name);
    if (slot != kIgnore) present[slot] = true;
    layout.slots.push_back(slot);
  }
  SourceLocation where{path, element.line};
  if (!present[kX] || !present[kY] || !present[kZ])
    throw InputError(where, "vertex element lacks x, y and z properties");
  int normals = present[kNX] + present[kNY] + present[kNZ];
  layout.hasNormals = normals == 3;
  if (normals > 0 && normals < 3)
    warnings.add(where, "vertex normals need nx, ny and nz; ignoring the incomplete normals");
  layout.hasUvs = present[kU] && present[kV];
  if (present[kU] != present[kV])
    warnings.add(where, "texture coordinates need both u and v; ignoring the lone one");
  return layout;
}

template <class Source>
void readVertices(Source& src, const PlyElement& element, const VertexLayout& layout,
                  MeshData& mesh) {
  // Reserve no more than the remaining bytes could hold, so a lying count cannot exhaust memory.
  size_t reserve = size_t(std::min<uint64_t>(element.count, src.bytesLeft()));
  mesh.positions.reserve(reserve);
  if (layout.hasNormals) mesh.normals.reserve(reserve);
  if (layout.hasUvs) mesh.uvs.reserve(2 * reserve);
  for (uint64_t i = 0; i < element.count; ++i) {
    double values[kSlotCount] = {};
    for (size_t p = 0; p < element.properties.size(); ++p) {
      int slot = layout.slots[p];
      if (slot == kIgnore)
        skipProperty(src, element.properties[p]);
      else
        values[slot] = src.next(element.properties[p].type);
    }
    const Vec3 position{float(values[kX]), float(values[kY]), float(values[kZ])};
    if (!std::isfinite(position.x) || !std::isfinite(position.y) || !std::isfinite(position.z))
      src.fail("non-finite vertex position");
    mesh.positions.push_back(position);
    if (layout.hasNormals)
      mesh.normals.push_back({float(values[kNX]), float(values[kNY]), float(values[kNZ])});
    if (layout.hasUvs) {
      mesh.uvs.push_back(float(values[kU]));
      mesh.uvs.push_back(float(values[kV]));
    }
  }
}

// Index of the face's vertex list property; throws if the element has none.
size_t faceListIndex(const PlyElement& element, const std::string& path) {
  for (size_t p = 0; p < element.properties.size(); ++p) {
    const PlyProperty& property = element.properties[p];
    if (property.name != "vertex_indices" && property.name != "vertex_index") continue;
    SourceLocation where{path, element.line};
    if (!property.isList)
      throw InputError(where, "face property '" + property.name + "' is not a list");
    if (!isIntegerType(property.type))
      throw InputError(where,
                       "face property '" + property.name + "' must have an integer item type");
    return p;
  }
  throw InputError({path, element.line}, "face element lacks a vertex_indices list");
}

template <class Source>
void readFaces(Source& src, const PlyElement& element, size_t listIndex, uint64_t vertexCount,
               MeshData& mesh) {
  const PlyProperty& list = element.properties[listIndex];
  std::vector<uint32_t> polygon;
  mesh.indices.reserve(size_t(std::min<uint64_t>(3 * element.count, src.bytesLeft())));
  for (uint64_t f = 0; f < element.count; ++f) {
    for (size_t p = 0; p < element.properties.size(); ++p) {
      if (p != listIndex) {
        skipProperty(src, element.properties[p]);
        continue;
      }
      double count = src.next(list.countType);
      if (count < 3) src.fail("face with " + std::to_string(int64_t(count)) + " vertices (at least 3 needed)");
      polygon.clear();
      for (uint64_t k = 0, n = uint64_t(count); k < n; ++k) {
        double index = src.next(list.type);
        if (index < 0 || index >= double(vertexCount))
          src.fail("vertex index " + std::to_string(int64_t(index)) + " out of range (" +
                   std::to_string(vertexCount) + " vertices)");
        polygon.push_back(uint32_t(index));
      }
      // Fan triangulation: exact for the convex polygons PLY exporters write.
      for (size_t k = 1; k + 1 < polygon.size(); ++k)
        mesh.indices.insert(mesh.indices.end(), {polygon[0], polygon[k], polygon[k + 1]});
    }
  }
}

template <class Source>
MeshData readBody(Source& src, const PlyHeader& header, const std::string& path,
                  Warnings& warnings) {
  const PlyElement* vertices = nullptr;
  for (const PlyElement& element : header.elements)
    if (element.name == "vertex" && !vertices) vertices = &element;
  if (!vertices)
    throw InputError({path, header.lineCount}, "PLY header declares no vertex element");
  if (vertices->count > 0xFFFFFFFFull)
    throw InputError({path, vertices->line}, "too many vertices for 32-bit indices");

  MeshData mesh;
  for (const PlyElement& element : header.elements) {
    if (&element == vertices) {
      readVertices(src, element, vertexLayout(element, path, warnings), mesh);
    } else if (element.name == "face") {
      readFaces(src, element, faceListIndex(element, path), vertices->count, mesh);
    } else {
      skipElement(src, element);
    }
  }
  return mesh;
}

}  // namespace

MeshData readPly(const std::string& path, Warnings& warnings) {
  std::string data = readWholeFile(path, "mesh file");
  PlyHeader header = HeaderParser(data, path, warnings).parse();
  if (header.format == PlyFormat::Ascii) {
    AsciiSource src(data, header, path);
    return readBody(src, header, path, warnings);
  }
  BinarySource src(data, header, path);
  return readBody(src, header, path, warnings);
}

}  // namespace erpt
