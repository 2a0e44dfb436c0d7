#include "support/mesh_bytes.h"

#include <zlib.h>

#include <stdexcept>

namespace erpt::test {

std::string serializeShape(const TestShape& shape, uint16_t version) {
  ByteWriter payload;
  payload.put(shape.flags);
  if (version == 4) payload.text(shape.name).put(uint8_t(0));
  payload.put(uint64_t(shape.positions.size() / 3)).put(uint64_t(shape.indices.size() / 3));
  auto reals = [&](const std::vector<double>& values) {
    for (double v : values) {
      if (shape.flags & kFloat64)
        payload.put(v);
      else
        payload.put(float(v));
    }
  };
  reals(shape.positions);
  reals(shape.normals);
  reals(shape.uvs);
  reals(shape.colors);
  for (uint32_t i : shape.indices) payload.put(i);

  std::string compressed(compressBound(uLong(payload.bytes.size())), '\0');
  uLongf size = uLongf(compressed.size());
  if (compress2(reinterpret_cast<Bytef*>(&compressed[0]), &size, reinterpret_cast<const Bytef*>(payload.bytes.data()),
                uLong(payload.bytes.size()), Z_BEST_COMPRESSION) != Z_OK)
    throw std::runtime_error("zlib could not compress a test shape");
  compressed.resize(size);

  ByteWriter out;
  out.put(uint16_t(0x041C)).put(version);
  return out.bytes + compressed;
}

std::string serializeFile(const std::vector<TestShape>& shapes, uint16_t version) {
  ByteWriter file;
  std::vector<uint64_t> offsets;
  for (const TestShape& shape : shapes) {
    offsets.push_back(file.bytes.size());
    file.text(serializeShape(shape, version));
  }
  for (uint64_t offset : offsets) {
    if (version == 4)
      file.put(offset);
    else
      file.put(uint32_t(offset));
  }
  file.put(uint32_t(shapes.size()));
  return file.bytes;
}

}  // namespace erpt::test
