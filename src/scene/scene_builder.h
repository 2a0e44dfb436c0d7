// Internal to the scene loader: walks Mitsuba XML elements and builds the Scene.
// One method per element category; plugin-specific code lives in xml_bsdfs.cpp,
// xml_shapes.cpp and xml_sensor.cpp.
#pragma once

#include <list>
#include <map>
#include <memory>
#include <optional>

#include "erpt/image_io.h"
#include "scene/mesh_io.h"
#include "erpt/scene_loader.h"
#include "xml_document.h"
#include "xml_properties.h"

namespace erpt::xml {

class SceneBuilder {
 public:
  SceneBuilder(Scene& scene, const LoadOptions& options);
  void loadFile(const std::string& path, int includeDepth);
  // The <scene> element of the file loadFile was first given: where problems of the scene as
  // a whole (nothing to render) are reported.
  const SourceLocation& sceneElement() const { return sceneElement_; }
  const Defines& defines() const { return defines_; }

 private:
  friend struct ElementReader;
  // Scene-level elements.
  void sceneChild(const Document& doc, const pugi::xml_node& node, int includeDepth);
  void include(const Document& doc, const pugi::xml_node& node, int includeDepth);
  void integrator(const Document& doc, const pugi::xml_node& node);
  void sensor(const Document& doc, const pugi::xml_node& node);
  void film(const Document& doc, const pugi::xml_node& node);
  // `parent`: the to_world of the `instance` this shape is a copy for (shapegroup members).
  // `group` >= 0: a shapegroup member to store once, in group space, as part of that
  // instance group's prototypes; returns false (and adds nothing) when the member cannot be
  // shared (scene.h's InstanceSet says which), so that each instance copies it instead.
  bool shape(const Document& doc, const pugi::xml_node& node, const Transform* parent = nullptr, int depth = 0,
             int group = -1);
  // `shapegroup` (kept by id) and `instance`: an Embree instance of the group's shareable
  // members, built when the group is first instanced, plus copies of the others, placed by
  // the instance's to_world. Instances inside shapegroups are copies all the way down.
  void instance(const Document& doc, const pugi::xml_node& node, Properties& props, const Transform* parent, int depth);
  struct GroupPlan {
    int group = -1;                        // InstanceSet group, -1 when no member is shareable
    std::vector<pugi::xml_node> copied;    // members each instance copies
  };
  GroupPlan planGroup(const Document& doc, const pugi::xml_node& groupNode, int depth);
  int emitter(const Document& doc, const pugi::xml_node& node, int shape);
  // A one-line warning when a mask's opacity is partial (neither ~0 nor ~1) anywhere it matters.
  void warnPartialOpacity(const ColorParam& opacity, const SourceLocation& where);
  // The texture a plugin wraps (normalmap, bumpmap, scale): named or nested, by value or <ref>; -1: none.
  int nestedTexture(const Document& doc, const Properties& props, const std::vector<pugi::xml_node>& children);
  // An `envmap`'s image, read, decoded and turned into the sampling tables.
  std::shared_ptr<const EnvironmentMap> environmentMap(const Document& doc, Properties& props, const SourceLocation& where);
  // `sky`, `sun` and `sunsky` (xml_daylight.cpp): adds the environment emitter they are drawn
  // into (or adds them to an earlier daylight emitter's map), and for a sun radius scale of 0
  // a directional light; returns the emitter's index.
  int daylight(const std::string& type, Properties& props, const SourceLocation& where);
  int bsdf(const Document& doc, const pugi::xml_node& node);
  int texture(const Document& doc, const pugi::xml_node& node);

  // Reads an element's parameters; nested objects it does not know go to `children`.
  Properties readProperties(const Document& doc, const pugi::xml_node& node,
                            std::vector<pugi::xml_node>* children = nullptr);
  Transform readTransform(const Document& doc, const pugi::xml_node& node);
  static Transform composedToWorld(const Properties& props, const Transform* parent, const SourceLocation& where);
  std::string blackbodyValue(const Document& doc, const pugi::xml_node& node);
  std::string attribute(const Document& doc, const pugi::xml_node& node, const char* name, bool required = true);
  // A referenced file's path, relative to the document. When it does not exist but a file
  // whose path differs only in letter case does (a scene made on Windows or macOS), that one,
  // with a warning at `where` naming both.
  std::string resolvePath(const Document& doc, const std::string& relative, const SourceLocation& where) const;
  // Throws InputError at `where` unless `path` exists and is not a directory ("<what> '<path>'
  // not found"). Errors inside the file come from its reader (referenced_file.h).
  void requireFile(const std::string& path, const SourceLocation& where, const std::string& what) const;
  int materialById(const Document& doc, const pugi::xml_node& node, const std::string& id);
  // Appends a shape's triangles, placed by toWorld, to `soup` (the world mesh or the
  // instance prototypes). `meshName` (the mesh file, or the shape's type) is named in errors
  // about its vertices, which are reported at the shape.
  void appendMesh(TriangleSoup& soup, MeshData& mesh, const Transform& toWorld, const Properties& props, int material,
                  int shapeIndex, const std::string& meshName);
  // An exact sphere, when to_world keeps it one (rotation, uniform scale, translation);
  // false otherwise (the caller tessellates it).
  bool appendSphere(Vec3 center, float radius, const Transform& toWorld, bool flip, int material, int shapeIndex);
  int defaultMaterial();

  Scene& scene_;
  Defines defines_;
  bool tessellateSpheres_ = false;
  int majorVersion_ = 0;
  SourceLocation sceneElement_;  // 0: Mitsuba 0.5/0.6 dialect, >= 2: Mitsuba 2/3 dialect
  std::list<Document> documents_;  // kept alive: nodes point into them
  std::map<std::string, int> materialIds_, textureIds_;
  std::map<std::string, pugi::xml_node> shapeGroups_;
  std::map<std::string, GroupPlan> groupPlans_;  // by shapegroup id, once it is instanced
  struct Daylight {
    RgbImage image;  // the sky and sun drawn so far, in the sky frame
    Transform toWorld;
    int emitter;     // the environment emitter showing them
  };
  std::optional<Daylight> daylight_;
  std::map<std::string, MeshData> instanceMeshes_;  // mesh files of shapegroup members, by file and options
  int defaultMaterial_ = -1;
  bool sawSensor_ = false;
};

}  // namespace erpt::xml
