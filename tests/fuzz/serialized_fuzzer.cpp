// Fuzz target: Mitsuba's .serialized reader. Mutated zlib streams rarely inflate, so the
// input is the shape's uncompressed record (its first byte picks version 3 or 4) and the
// target compresses it and adds the header and the dictionary: the mutations reach the
// record's flags, counts and arrays. (The raw file path, zlib errors included, is covered by
// mesh_readers_test.)
#include <zlib.h>

#include <vector>

#include "scene/mesh_io.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const uint16_t version = (data[0] & 1) ? 4 : 3;
  uLongf packedSize = compressBound(uLong(size - 1));
  std::vector<uint8_t> file(4 + packedSize);
  file[0] = 0x1C, file[1] = 0x04, file[2] = uint8_t(version), file[3] = 0;
  if (compress2(file.data() + 4, &packedSize, data + 1, uLong(size - 1), 6) != Z_OK) return 0;
  file.resize(4 + packedSize);
  file.insert(file.end(), version == 4 ? 8 : 4, 0);  // shape 0's offset: 0
  file.insert(file.end(), {1, 0, 0, 0});             // one shape
  const std::string path = erpt::fuzz::writeInput("mesh.serialized", file.data(), file.size());
  erpt::Warnings warnings;
  erpt::fuzz::expectCleanFailure([&] { erpt::readSerialized(path, 0, warnings); }, erpt::fuzz::Place::File);
  return 0;
}
