// A scene loaded with what the stage kernels read beside it (tracer, camera, box filter, light
// sampler) and a StageContext over them, for the stage tests that call kernels directly.
#pragma once

#include <cstdint>
#include <string>

#include "erpt/scene_loader.h"
#include "models/camera.h"
#include "stages/stages.h"
#include "tracer/tracer.h"

namespace erpt::test {

struct StageWorld {
  Scene scene;
  Tracer tracer;
  Camera camera;
  PixelFilter box{FilterKind::Box};
  LightSampler lights;
  StageContext ctx;

  // The scene file at `path`, rendered at width x height with `spp` samples of seed `seed`,
  // paths of any length.
  StageWorld(const std::string& path, uint64_t seed, int width, int height, int spp)
      : scene(loadScene(path)),
        tracer(scene),
        camera(scene.camera, width, height),
        lights(scene),
        ctx{scene, camera, box, lights, seed, width, height, spp, -1} {}
  StageWorld(const StageWorld&) = delete;
  StageWorld& operator=(const StageWorld&) = delete;
};

}  // namespace erpt::test
