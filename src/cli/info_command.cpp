#include <iostream>

#include <CLI/CLI.hpp>

#include "commands.h"
#include "erpt/scene_names.h"
#include "erpt/scene_loader.h"

namespace erpt::cli {

void addInfoCommand(CLI::App& app, InfoArgs& a) {
  CLI::App* cmd = app.add_subcommand("info", "Print what a scene contains and any warnings");
  cmd->add_option("scene", a.scene, "Scene file (Mitsuba 0.6 or 3 XML)")->required();
  cmd->add_option("-D,--define", a.defines, "Override a scene <default>: -D name=value (repeatable)");
  cmd->add_flag("--tessellate-spheres", a.tessellateSpheres, "Load sphere shapes as triangle meshes");
}


int runInfo(const InfoArgs& a) {
  LoadOptions load;
  load.defines = parseDefines(a.defines);
  load.tessellateSpheres = a.tessellateSpheres;
  Scene scene = loadScene(a.scene, load);
  std::cout << "scene:      " << a.scene << "\n"
            << "film:       " << scene.film.width << "x" << scene.film.height << ", " << scene.integrator.spp << " spp\n"
            << "integrator: " << scene.integrator.type << " (max depth " << scene.integrator.maxDepth << ")\n"
            << "triangles:  " << scene.mesh.triangleCount() << " (" << scene.droppedDegenerateTriangles
            << " degenerate dropped)\n"
            << "vertices:   " << scene.mesh.vertexCount() << "\n"
            << "spheres:    " << scene.spheres.count() << " (exact)\n"
            << "instances:  " << scene.instances.count() << " of " << scene.instances.groupCount() << " shapegroup(s), "
            << scene.instances.prototypes.triangleCount() << " triangles stored, "
            << scene.instances.instancedTriangleCount() << " placed\n"
            << "shapes:     " << scene.shapes.size() << "\n";
  for (const ShapeInfo& s : scene.shapes) {
    std::cout << "  " << s.type << (s.id.empty() ? "" : " '" + s.id + "'") << ": ";
    if (s.sphere >= 0)
      std::cout << "exact sphere, radius " << scene.spheres.radius[size_t(s.sphere)] << "\n";
    else
      std::cout << s.triangleCount << " triangles" << (s.group >= 0 ? " (instanced shapegroup member)" : "") << "\n";
  }
  std::cout << "lights:     " << scene.emitters.size() << "\n";
  for (const Emitter& e : scene.emitters)
    std::cout << "  " << emitterKindName(e) << " (" << e.radiance.x << ", " << e.radiance.y << ", " << e.radiance.z << ")"
              << (e.map ? " mean, " + std::to_string(e.map->width()) + "x" + std::to_string(e.map->height()) + " pixels" : "")
              << "\n";
  std::cout << "materials:  " << scene.materials.size() << "\n";
  for (const Material& m : scene.materials)
    std::cout << "  " << m.name << ": " << bsdfKindName(m.kind) << (m.twoSided ? ", two-sided" : "") << "\n";
  std::cout << "textures:   " << scene.textures.size() << "\n"
            << "warnings:   " << scene.warnings.messages.size() << "\n";
  for (const std::string& w : scene.warnings.messages) std::cout << "  " << w << "\n";
  return 0;
}

}  // namespace erpt::cli
