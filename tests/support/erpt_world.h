// A scene with everything ERPT's stages read (tracer, camera, filter, lights, film density)
// and a store of path-traced seeds, for stage-level tests.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "stages/chain_stages.h"
#include "erpt/scene_loader.h"
#include "tracer/tracer.h"

namespace erpt::test {

// A thin lens to replace a scene's sensor with (radius 0: the scene's own).
struct ThinLens {
  float radius = 0, focusDistance = 0;
};

struct ErptWorld {
  Scene scene;
  int width, height;
  std::unique_ptr<Tracer> tracer;
  std::unique_ptr<Camera> camera;
  std::unique_ptr<PixelFilter> filter;
  std::unique_ptr<LightSampler> lights;
  std::unique_ptr<FilmDensity> density;
  SeedStore seeds;

  // Loads `sceneFile` at size x size (filter: `filter`) and path-traces `spp` samples per pixel
  // with seed recording.
  ErptWorld(const std::string& sceneFile, int size, int spp, FilterKind filter, uint64_t seed = 1,
            ThinLens lens = {});
  MeasureContext measure() const { return {scene, *lights, *camera, *density}; }
  StepConfig stepContext(MutationStrategy strategy) const;
  // The seed's path as PathVertex values.
  int seedPath(size_t seed, PathVertex* out) const;
  // The first surface point along a ray, traced alone (nullopt: it missed or was refused).
  std::optional<SurfacePoint> traceOne(Vec3 origin, Vec3 dir) const;
};

// The library's chain queues, and the library's chain step stopped before accept, so tests can
// look between the stages.
struct ChainQueues : StepQueues {
  using StepQueues::StepQueues;
  // Starts chains in slots 0, 1, ... at the world's seeds in order, skipping seeds too long
  // for a chain or without energy, until the queue is full; chain keys streamKey(keySeed,
  // seed, 0). Returns how many were loaded.
  // `stride` > 1 takes every stride-th seed (spreading the chains over the image); `keep`, when
  // given, takes only the seeds whose signature it accepts.
  size_t loadSeeds(const ErptWorld& world, uint32_t chainLength, float energyPerStep, uint64_t keySeed,
                   size_t stride = 1, bool (*keep)(const uint8_t* kinds, int n) = nullptr);
  // ChainStep::propose: mutate -> (intersect -> trace)* -> connect; stops before accept.
  // `chooser`: the mutate stage's choice (null: ERPT's).
  void propose(const ErptWorld& world, const StepConfig& ctx, const ProposalPolicy* chooser = nullptr);
};

}  // namespace erpt::test
