// Checkpoint files (`erpt render --checkpoint FILE`, `erpt resume FILE`; docs/long-renders.md):
// a render's state after a whole number of sample passes, with what is needed to continue it
// and to refuse it where it does not belong.
//
// Layout: "ERPTCKPT", format version, the build's version, the scene's fingerprint, the render
// command's arguments, the RenderState, then a 64-bit FNV-1a checksum of everything before it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "erpt/render_state.h"
#include "erpt/scene.h"

namespace erpt {

struct Checkpoint {
  uint64_t sceneFingerprint = 0;
  std::string directory;          // the working directory the render ran in (paths in args are relative to it)
  int32_t rank = 0, ranks = 1;    // which process of a split render (MPI) this is the state of
  std::vector<std::string> args;  // the render command's arguments, from the scene on
  RenderState state;
};

// What a checkpoint must match to be resumed: the scene file's bytes and the loaded geometry
// (vertex positions and triangles, spheres, material and emitter counts), so an edited scene,
// or a changed mesh file it names, is refused. Textures are not part of it.
uint64_t sceneFingerprint(const Scene& scene);

// Atomic (temporary file, then rename): a crash while writing keeps the previous checkpoint.
void writeCheckpointAtomic(const std::string& path, const Checkpoint& checkpoint);
// Throws InputError naming the file and the cause for a missing, truncated or corrupt file, or
// one written by another version of erpt.
Checkpoint readCheckpoint(const std::string& path);

}  // namespace erpt
