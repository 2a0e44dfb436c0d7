// Checkpoint files (checkpoint.h): what is written is read back, and a truncated, corrupt,
// foreign or other-version file is refused with an error naming the file.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include "io/checkpoint.h"
#include "erpt/error.h"
#include "erpt/scene_loader.h"
#include "support/test_support.h"

namespace erpt {
namespace {

std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}
void writeBytes(const std::string& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

Checkpoint example() {
  Checkpoint c;
  c.sceneFingerprint = 0x0123456789abcdefull;
  c.directory = "/some/dir";
  c.args = {"scene.xml", "-o", "out.exr", "--spp", "64", "--checkpoint", "c.ckpt"};
  c.state.passesDone = 17;
  for (int i = 0; i < 1000; ++i) c.state.bytes.push_back(uint8_t(i * 7));
  return c;
}

// The error names the file and says why.
void expectRefused(const std::string& path, const std::string& why) {
  try {
    readCheckpoint(path);
    ADD_FAILURE() << "accepted: " << why;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
  }
}

TEST(CheckpointFile, RoundTrips) {
  test::TempDir dir;
  const std::string path = dir.file("c.ckpt");
  const Checkpoint c = example();
  writeCheckpointAtomic(path, c);
  const Checkpoint r = readCheckpoint(path);
  EXPECT_EQ(r.sceneFingerprint, c.sceneFingerprint);
  EXPECT_EQ(r.directory, c.directory);
  EXPECT_EQ(r.args, c.args);
  EXPECT_EQ(r.state.passesDone, c.state.passesDone);
  EXPECT_EQ(r.state.bytes, c.state.bytes);
}

TEST(CheckpointFile, TruncatedCorruptForeignAndOtherVersionFilesAreRefused) {
  test::TempDir dir;
  const std::string path = dir.file("c.ckpt");
  writeCheckpointAtomic(path, example());
  const std::string good = readBytes(path);
  const std::string bad = dir.file("bad.ckpt");
  for (size_t keep : {size_t(0), size_t(5), size_t(8), size_t(20), good.size() / 2, good.size() - 1}) {
    SCOPED_TRACE("cut to " + std::to_string(keep) + " bytes");
    writeBytes(bad, good.substr(0, keep));
    try {
      readCheckpoint(bad);
      ADD_FAILURE() << "a truncated checkpoint was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
  }
  for (size_t at : {size_t(40), good.size() / 2, good.size() - 3}) {
    std::string flipped = good;
    flipped[at] = char(flipped[at] ^ 0x10);
    writeBytes(bad, flipped);
    expectRefused(bad, "corrupt");
  }
  writeBytes(bad, "<scene version=\"3.0.0\"/>");
  expectRefused(bad, "not an erpt checkpoint");
  std::string otherFormat = good;
  otherFormat[8] = char(otherFormat[8] + 1);  // the format version follows the magic
  writeBytes(bad, otherFormat);
  expectRefused(bad, "same version");
  expectRefused(dir.file("missing.ckpt"), "cannot open");
}

// The fingerprint follows the scene file and its geometry.
TEST(CheckpointFile, SceneFingerprintChangesWithTheSceneAndItsGeometry) {
  test::TempDir dir;
  const std::string xml = R"(<scene version="3.0.0"><shape type="obj"><string name="filename" value="m.obj"/></shape></scene>)";
  dir.write("m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string scenePath = dir.write("s.xml", xml);
  const uint64_t a = sceneFingerprint(loadScene(scenePath));
  EXPECT_EQ(sceneFingerprint(loadScene(scenePath)), a);
  dir.write("m.obj", "v 0 0 0\nv 1 0 0\nv 0 2 0\nf 1 2 3\n");
  const uint64_t b = sceneFingerprint(loadScene(scenePath));
  EXPECT_NE(b, a);
  dir.write("s.xml", xml + "\n");
  EXPECT_NE(sceneFingerprint(loadScene(scenePath)), b);
}

}  // namespace
}  // namespace erpt
