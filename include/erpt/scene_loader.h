// Loads Mitsuba scene descriptions (0.5/0.6 dialect with camelCase names, and the 2.x/3.x
// dialect with snake_case names) into a Scene.
#pragma once

#include <map>
#include <string>

#include "erpt/scene.h"

namespace erpt {

struct LoadOptions {
  // `-D name=value`: overrides the scene's <default> values (and defines new ones).
  std::map<std::string, std::string> defines;
  // Load `sphere` shapes as triangle meshes (256 x 512) instead of exact spheres.
  bool tessellateSpheres = false;
};

// Throws InputError (file:line: cause) on malformed input; warnings land in Scene::warnings.
Scene loadScene(const std::string& path, const LoadOptions& options = {});

}  // namespace erpt
