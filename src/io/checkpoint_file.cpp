#include "io/checkpoint.h"

#include <cstring>

#include "core/byte_stream.h"
#include "erpt/error.h"
#include "io/file_util.h"
#include "erpt/image_io.h"

#ifndef ERPT_VERSION
#define ERPT_VERSION "unknown"
#endif

namespace erpt {

namespace {
constexpr char kMagic[8] = {'E', 'R', 'P', 'T', 'C', 'K', 'P', 'T'};
// Bump when any integrator's state layout changes (sample_passes.h's save hooks).
// 2: a mutation kind more in the chain counters (the bidirectional mutation); 3: the chains'
// proposal tallies hold the acceptance map too (--chain-maps).
constexpr uint32_t kFormatVersion = 4;

struct Fnv1a {
  uint64_t h = 0xcbf29ce484222325ull;
  void add(const void* data, size_t n) {
    const auto* p = static_cast<const uint8_t*>(data);
    for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
  }
  template <class T>
  void addVector(const std::vector<T>& v) {
    const uint64_t n = v.size();
    add(&n, sizeof n);
    add(v.data(), v.size() * sizeof(T));
  }
};

uint64_t checksum(const uint8_t* data, size_t n) {
  Fnv1a f;
  f.add(data, n);
  return f.h;
}
}  // namespace

uint64_t sceneFingerprint(const Scene& scene) {
  Fnv1a f;
  if (!scene.file.empty()) {
    const std::string xml = readWholeFile(scene.file, "scene file");
    f.add(xml.data(), xml.size());
  }
  const TriangleSoup& m = scene.mesh;
  for (const auto* v : {&m.px, &m.py, &m.pz}) f.addVector(*v);
  for (const auto* v : {&m.v0, &m.v1, &m.v2}) f.addVector(*v);
  const uint64_t counts[] = {scene.spheres.count(), scene.materials.size(), scene.emitters.size(),
                             scene.shapes.size(), uint64_t(scene.instances.instancedTriangleCount())};
  f.add(counts, sizeof counts);
  return f.h;
}

void writeCheckpointAtomic(const std::string& path, const Checkpoint& c) {
  ByteWriter w;
  for (char ch : kMagic) w.put(ch);
  w.put(kFormatVersion);
  w.putString(ERPT_VERSION);
  w.put(c.sceneFingerprint);
  w.putString(c.directory);
  w.put(c.rank), w.put(c.ranks);
  w.put(uint64_t(c.args.size()));
  for (const std::string& a : c.args) w.putString(a);
  w.put(int32_t(c.state.passesDone));
  w.putVector(c.state.bytes);
  std::vector<uint8_t> bytes = w.take();
  const uint64_t sum = checksum(bytes.data(), bytes.size());
  const auto* p = reinterpret_cast<const uint8_t*>(&sum);
  bytes.insert(bytes.end(), p, p + sizeof sum);
  writeBytesAtomic(path, bytes);
}

Checkpoint readCheckpoint(const std::string& path) {
  const std::string data = readWholeFile(path, "checkpoint");
  const auto* bytes = reinterpret_cast<const uint8_t*>(data.data());
  if (data.size() < sizeof kMagic || std::memcmp(bytes, kMagic, sizeof kMagic) != 0)
    throw InputError({path, 0}, "not an erpt checkpoint");
  if (data.size() < sizeof kMagic + sizeof(uint64_t)) throw InputError({path, 0}, "truncated checkpoint");
  const size_t body = data.size() - sizeof(uint64_t);
  uint64_t stored;
  std::memcpy(&stored, bytes + body, sizeof stored);
  ByteReader r(bytes + sizeof kMagic, body - sizeof kMagic);
  try {
    const uint32_t format = r.get<uint32_t>();
    const std::string version = r.getString(256);
    if (format != kFormatVersion || version != ERPT_VERSION)
      throw InputError({path, 0}, "checkpoint written by erpt " + version + " (format " + std::to_string(format) +
                                      "); this is erpt " + ERPT_VERSION + " (format " + std::to_string(kFormatVersion) +
                                      "): resume it with the same version");
    if (checksum(bytes, body) != stored) throw InputError({path, 0}, "corrupt or truncated checkpoint (checksum mismatch)");
    Checkpoint c;
    r.get(c.sceneFingerprint);
    c.directory = r.getString();
    r.get(c.rank), r.get(c.ranks);
    const uint64_t n = r.get<uint64_t>();
    if (n > 10000) throw InputError({path, 0}, "corrupt checkpoint (absurd argument count)");
    for (uint64_t i = 0; i < n; ++i) c.args.push_back(r.getString());
    c.state.passesDone = r.get<int32_t>();
    const uint64_t stateBytes = r.get<uint64_t>();
    if (stateBytes != r.remaining()) throw InputError({path, 0}, "corrupt checkpoint (state size does not match the file)");
    c.state.bytes.assign(bytes + (body - stateBytes), bytes + body);
    return c;
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError({path, 0}, std::string("corrupt or truncated checkpoint (") + e.what() + ")");
  }
}

}  // namespace erpt
