// <shape> and <emitter> plugins, and the checks every mesh goes through before it joins
// the scene: finite positions, valid indices, degenerate triangles dropped and counted.
#include "scene/mesh_io.h"
#include "referenced_file.h"
#include "scene_builder.h"

namespace erpt::xml {

// An instance's or shape's to_world after the transforms of the instances around it; each
// factor was checked when it was read, the product is checked here.
Transform SceneBuilder::composedToWorld(const Properties& props, const Transform* parent, const SourceLocation& where) {
  if (!parent) return props.getTransform("to_world");
  const Transform toWorld = *parent * props.getTransform("to_world");
  const std::string defect = toWorld.defect();
  if (!defect.empty()) throw InputError(where, "to_world composed with the enclosing instances' transforms " + defect);
  return toWorld;
}

void SceneBuilder::instance(const Document& doc, const pugi::xml_node& node, Properties& props, const Transform* parent,
                            int depth) {
  const SourceLocation where = doc.where(node);
  if (attribute(doc, node, "type") == "shapegroup") {
    const std::string id = attribute(doc, node, "id", false);
    if (id.empty()) throw InputError(where, "a shapegroup needs an id (instances refer to it)");
    shapeGroups_[id] = node;
    props.warnUnused(scene_.warnings);
    return;
  }
  pugi::xml_node ref = node.child("ref");
  if (!ref) throw InputError(where, "an instance needs a <ref id=\"...\"/> to a shapegroup");
  const std::string id = attribute(doc, ref, "id");
  const auto group = shapeGroups_.find(id);
  if (group == shapeGroups_.end()) throw InputError(doc.where(ref), "no shapegroup with id '" + id + "' before this instance");
  if (depth >= 8) throw InputError(where, "instances nested more than 8 deep (a shapegroup instancing itself?)");
  const Transform toWorld = composedToWorld(props, parent, where);
  props.warnUnused(scene_.warnings);
  const double det = toWorld.determinant3x3();
  if (!(std::abs(det) > 0)) {
    scene_.warnings.add(where, "instance to_world is singular (a zero scale); the instance is skipped");
    return;
  }
  if (parent) {  // inside a shapegroup: copies
    for (const pugi::xml_node& member : group->second.children("shape")) shape(doc, member, &toWorld, depth + 1);
    return;
  }
  auto plan = groupPlans_.find(id);
  if (plan == groupPlans_.end()) plan = groupPlans_.emplace(id, planGroup(doc, group->second, depth)).first;
  if (plan->second.group >= 0) {
    InstanceSet& in = scene_.instances;
    // Embree places the shared prototypes by this transform while tracing: their world-space
    // corners must be finite floats, as every copied vertex is (appendMesh).
    const Vec3 lo = in.groupLower[size_t(plan->second.group)], hi = in.groupUpper[size_t(plan->second.group)];
    for (int corner = 0; corner < 8; ++corner)
      if (!isFinite(toWorld.point(Vec3(corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y, corner & 4 ? hi.z : lo.z))))
        throw InputError(where, "instance to_world places the shapegroup '" + id + "' beyond single-precision range");
    in.group.push_back(uint32_t(plan->second.group));
    in.firstPrimitive.push_back(0);  // numbered when the scene has loaded
    in.toWorld.push_back(toWorld);
    Transform normalToWorld = toWorld.inverse();
    for (int r = 0; r < 4; ++r)
      for (int c = r + 1; c < 4; ++c) std::swap(normalToWorld(r, c), normalToWorld(c, r));
    in.normalToWorld.push_back(normalToWorld);
    in.mirrored.push_back(det < 0);
  }
  for (const pugi::xml_node& member : plan->second.copied) shape(doc, member, &toWorld, depth + 1);
}

SceneBuilder::GroupPlan SceneBuilder::planGroup(const Document& doc, const pugi::xml_node& groupNode, int depth) {
  InstanceSet& in = scene_.instances;
  TriangleSoup& prototypes = in.prototypes;
  const int g = int(in.groupCount());
  const uint32_t firstTriangle = uint32_t(prototypes.triangleCount()), firstVertex = uint32_t(prototypes.vertexCount());
  GroupPlan plan;
  for (const pugi::xml_node& member : groupNode.children("shape"))
    if (!shape(doc, member, nullptr, depth + 1, g)) plan.copied.push_back(member);
  const uint32_t count = uint32_t(prototypes.triangleCount()) - firstTriangle;
  if (count == 0) return plan;
  Vec3 lo(1e30f), hi(-1e30f);
  for (uint32_t i = firstVertex; i < prototypes.vertexCount(); ++i)
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], prototypes.position(i)[a]);
      hi[a] = std::max(hi[a], prototypes.position(i)[a]);
    }
  in.groupFirstTriangle.push_back(firstTriangle);
  in.groupTriangleCount.push_back(count);
  in.groupLower.push_back(lo);
  in.groupUpper.push_back(hi);
  plan.group = g;
  return plan;
}

bool SceneBuilder::shape(const Document& doc, const pugi::xml_node& node, const Transform* parent, int depth,
                         int group) {
  std::string type = attribute(doc, node, "type");
  // Shared members are meshes; spheres stay exact per copy, instances nest as copies.
  if (group >= 0 && (type == "shapegroup" || type == "instance" || type == "sphere")) return false;
  std::vector<pugi::xml_node> children;
  Properties props = readProperties(doc, node, &children);
  SourceLocation where = doc.where(node);
  if (type == "shapegroup" || type == "instance") {
    instance(doc, node, props, parent, depth);
    return true;
  }

  // The mesh, in object space (empty for an exact sphere).
  MeshData mesh;
  bool exactSphere = false;
  Vec3 sphereCenter(0.0f);
  float sphereRadius = 1;
  std::string meshName = type;           // the mesh file, for messages about its vertices
  SourceLocation fileWhere = where;      // the XML line that names the mesh file
  auto meshFile = [&]() {
    const Property* file = props.find("filename");
    if (!file) throw InputError(where, "shape '" + type + "' needs a 'filename'");
    std::string path = resolvePath(doc, file->value, file->where);
    requireFile(path, file->where, "mesh file");
    meshName = path;
    fileWhere = file->where;
    return path;
  };
  // Members of a shapegroup are loaded once per instance: their files are read once.
  auto readOnce = [&](const std::string& key, auto read) -> MeshData {
    auto readHere = [&] { return readReferencedFile(fileWhere, read); };
    if (!parent) return readHere();
    const auto cached = instanceMeshes_.find(key);
    if (cached != instanceMeshes_.end()) return cached->second;
    return instanceMeshes_[key] = readHere();
  };
  if (type == "obj") {
    std::string path = meshFile();
    const bool flipUv = props.getBool("flip_tex_coords", true);
    mesh = readOnce("obj|" + path + "|" + std::to_string(flipUv), [&] { return readObj(path, flipUv, scene_.warnings); });
  } else if (type == "ply") {
    std::string path = meshFile();
    mesh = readOnce("ply|" + path, [&] { return readPly(path, scene_.warnings); });
  } else if (type == "serialized") {
    std::string path = meshFile();
    const int index = props.getInt("shape_index", 0);
    mesh = readOnce("serialized|" + path + "|" + std::to_string(index),
                    [&] { return readSerialized(path, index, scene_.warnings); });
  } else if (type == "rectangle") {
    mesh = makeRectangle();
  } else if (type == "cube") {
    mesh = makeCube();
  } else if (type == "disk") {
    mesh = makeDisk();
  } else if (type == "cylinder") {
    const float radius = props.getFloat("radius", 1.0f);
    if (!(radius > 0)) throw InputError(props.find("radius")->where, "cylinder radius must be positive");
    const Vec3 p0 = props.getPoint("p0", Vec3(0.0f)), p1 = props.getPoint("p1", Vec3(0.0f, 0.0f, 1.0f));
    if (!(length(p1 - p0) > 0)) throw InputError(where, "cylinder p0 and p1 must differ");
    mesh = makeCylinder(p0, p1, radius);
  } else if (type == "sphere") {
    sphereRadius = props.getFloat("radius", 1.0f);
    if (!(sphereRadius > 0) || !std::isfinite(sphereRadius))
      throw InputError(props.find("radius")->where, "sphere radius must be positive and finite");
    sphereCenter = props.getPoint("center", Vec3(0.0f));
    exactSphere = !tessellateSpheres_;
  } else {
    scene_.warnings.add(where, "shape '" + type + "' is not supported; skipped");
    return true;
  }
  if (props.getBool("face_normals", false)) mesh.normals.clear();
  // Mitsuba 0.6 OBJ/PLY option; normals are computed from the mesh when absent anyway.
  props.find("max_smooth_angle");

  int material = -1;
  std::vector<pugi::xml_node> emitters;
  for (const pugi::xml_node& child : children) {
    std::string tag = child.name();
    if (tag == "bsdf") material = bsdf(doc, child);
    else if (tag == "ref") material = materialById(doc, child, attribute(doc, child, "id"));
    else if (tag == "emitter") emitters.push_back(child);
    else scene_.warnings.add(doc.where(child), "<" + tag + "> inside <shape> is not supported; ignored");
  }
  if (material < 0) material = defaultMaterial();
  const Material& surface = scene_.materials[size_t(material)];
  if (group >= 0 && (!emitters.empty() || surface.masked || surface.adjustsShadingFrame())) return false;
  if (exactSphere && scene_.materials[size_t(material)].masked) {
    // Cut-outs are an intersection filter on the triangles, whose uvs the mask reads.
    scene_.warnings.add(where, "a masked sphere is tessellated (cut-outs apply to triangles)");
    exactSphere = false;
  }
  if (exactSphere && scene_.materials[size_t(material)].adjustsShadingFrame()) {
    // The maps and anisotropic roughness read the triangles' uv derivatives.
    scene_.warnings.add(where, "a sphere with a normal or bump map or anisotropic roughness is tessellated (they "
                               "follow the triangles' uv derivatives)");
    exactSphere = false;
  }

  int shapeIndex = int(scene_.shapes.size());
  ShapeInfo info;
  info.type = type;
  info.id = attribute(doc, node, "id", false);
  info.where = where;
  info.group = group;
  TriangleSoup& soup = group >= 0 ? scene_.instances.prototypes : scene_.mesh;
  info.firstTriangle = uint32_t(soup.triangleCount());
  scene_.shapes.push_back(info);
  const Transform toWorld = composedToWorld(props, parent, where);
  const bool flip = props.getBool("flip_normals", false);
  if (exactSphere && !appendSphere(sphereCenter, sphereRadius, toWorld, flip, material, shapeIndex)) {
    scene_.warnings.add(where, "to_world scales the sphere unevenly; it is tessellated (an ellipsoid)");
    exactSphere = false;
  }
  if (type == "sphere" && !exactSphere) mesh = makeSphere(sphereCenter, sphereRadius);
  if (!exactSphere) appendMesh(soup, mesh, toWorld, props, material, shapeIndex, meshName);
  scene_.shapes.back().triangleCount = uint32_t(soup.triangleCount()) - info.firstTriangle;

  if (!emitters.empty() && scene_.materials[size_t(material)].masked)
    scene_.warnings.add(where, "an emitting shape is not cut by its mask (light sampling picks points by area)");
  for (const pugi::xml_node& e : emitters) {
    int index = emitter(doc, e, shapeIndex);
    if (index < 0) continue;
    for (uint32_t t = info.firstTriangle; t < scene_.mesh.triangleCount(); ++t) scene_.mesh.emitter[t] = index;
    if (exactSphere) scene_.spheres.emitter.back() = index;
  }
  props.warnUnused(scene_.warnings);
  return true;
}

void SceneBuilder::appendMesh(TriangleSoup& soup, MeshData& mesh, const Transform& toWorld, const Properties& props,
                              int material, int shapeIndex, const std::string& meshName) {
  const bool flip = props.getBool("flip_normals", false);
  const bool hasNormals = !mesh.normals.empty(), hasUvs = !mesh.uvs.empty();
  const uint32_t base = uint32_t(soup.vertexCount());
  const size_t vertexCount = mesh.positions.size();
  std::vector<uint8_t> goodNormal(vertexCount, 0);
  for (size_t i = 0; i < vertexCount; ++i) {
    Vec3 p = toWorld.point(mesh.positions[i]);
    if (!isFinite(p))
      throw InputError(scene_.shapes[shapeIndex].where, "non-finite vertex position after to_world (" +
                                                            meshName + ", vertex " + std::to_string(i) + ")");
    soup.px.push_back(p.x);
    soup.py.push_back(p.y);
    soup.pz.push_back(p.z);
    Vec3 n(0.0f);
    if (hasNormals) {
      n = toWorld.normal(mesh.normals[i]);
      float len = length(n);
      goodNormal[i] = std::isfinite(len) && len > 0;
      n = goodNormal[i] ? n / len * (flip ? -1.0f : 1.0f) : Vec3(0.0f);
    }
    soup.nx.push_back(n.x);
    soup.ny.push_back(n.y);
    soup.nz.push_back(n.z);
    soup.u.push_back(hasUvs ? mesh.uvs[2 * i] : 0.0f);
    soup.v.push_back(hasUvs ? mesh.uvs[2 * i + 1] : 0.0f);
  }
  size_t dropped = 0;
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
    if (a >= vertexCount || b >= vertexCount || c >= vertexCount)
      throw InputError(scene_.shapes[shapeIndex].where,
                       meshName + ": triangle " + std::to_string(t / 3) + " refers to a vertex that does not exist");
    if (flip) std::swap(b, c);  // flipping the winding flips the face normal
    Vec3 pa = soup.position(base + a);
    Vec3 n = cross(soup.position(base + b) - pa, soup.position(base + c) - pa);
    if (!(length(n) > 0) || !isFinite(n)) {
      ++dropped;
      continue;
    }
    soup.v0.push_back(base + a);
    soup.v1.push_back(base + b);
    soup.v2.push_back(base + c);
    soup.material.push_back(material);
    soup.emitter.push_back(-1);
    soup.shape.push_back(shapeIndex);
    soup.smooth.push_back(goodNormal[a] && goodNormal[b] && goodNormal[c]);
  }
  if (dropped > 0) {
    scene_.droppedDegenerateTriangles += dropped;
    scene_.warnings.add(scene_.shapes[shapeIndex].where,
                        "dropped " + std::to_string(dropped) + " degenerate triangle(s) of this shape");
  }
  if (soup.triangleCount() == scene_.shapes[shapeIndex].firstTriangle)
    scene_.warnings.add(scene_.shapes[shapeIndex].where, "shape has no triangles");
}

bool SceneBuilder::appendSphere(Vec3 center, float radius, const Transform& toWorld, bool flip, int material,
                                int shapeIndex) {
  // Columns of the linear part: a similarity has three orthogonal columns of one length.
  const Vec3 ax = toWorld.vector({1, 0, 0}), ay = toWorld.vector({0, 1, 0}), az = toWorld.vector({0, 0, 1});
  const float scale = length(ax);
  const float tolerance = 1e-4f * scale;
  if (!(scale > 0) || std::abs(length(ay) - scale) > tolerance || std::abs(length(az) - scale) > tolerance ||
      std::abs(dot(ax, ay)) > tolerance * scale || std::abs(dot(ax, az)) > tolerance * scale ||
      std::abs(dot(ay, az)) > tolerance * scale)
    return false;
  const Vec3 c = toWorld.point(center);
  const float r = radius * scale;
  if (!isFinite(c) || !std::isfinite(r))
    throw InputError(scene_.shapes[shapeIndex].where, "non-finite sphere centre or radius after to_world");
  SphereSet& s = scene_.spheres;
  s.cx.push_back(c.x);
  s.cy.push_back(c.y);
  s.cz.push_back(c.z);
  s.radius.push_back(r);
  Frame frame;
  frame.s = ax / scale;
  frame.t = ay / scale;
  frame.n = az / scale;
  s.frame.push_back(frame);
  s.material.push_back(material);
  s.emitter.push_back(-1);
  s.shape.push_back(shapeIndex);
  s.flipped.push_back(flip);
  scene_.shapes[shapeIndex].sphere = int(s.count()) - 1;
  return true;
}

std::shared_ptr<const EnvironmentMap> SceneBuilder::environmentMap(const Document& doc, Properties& props,
                                                                   const SourceLocation& where) {
  const Property* file = props.find("filename");
  if (!file) throw InputError(where, "envmap needs a 'filename'");
  const std::string path = resolvePath(doc, file->value, file->where);
  requireFile(path, file->where, "environment map file");
  bool srgb = false;
  RgbImage image = readReferencedFile(file->where, [&] { return readImage(path, &srgb); });
  // Mitsuba 0.6's gamma override: 0 (default) as the file says, -1 sRGB, 1 linear, else a power.
  const float gamma = props.getFloat("gamma", 0.0f);
  for (Color& c : image.pixels) {
    if (gamma == -1 || (gamma == 0 && srgb)) c = srgbToLinear(c);
    else if (gamma > 0 && gamma != 1) c = Color(std::pow(c.x, gamma), std::pow(c.y, gamma), std::pow(c.z, gamma));
  }
  props.find("cache");  // Mitsuba 0.6's MIP-map cache file: nothing to cache here
  try {
    return std::make_shared<const EnvironmentMap>(image, props.getFloat("scale", 1.0f), props.getTransform("to_world"));
  } catch (const std::invalid_argument& e) {
    throw InputError(file->where, "'" + path + "': " + e.what());
  }
}

int SceneBuilder::emitter(const Document& doc, const pugi::xml_node& node, int shape) {
  Properties props = readProperties(doc, node);
  std::string type = attribute(doc, node, "type");
  SourceLocation where = doc.where(node);
  Emitter e;
  if (type == "area") {
    if (shape < 0) throw InputError(where, "an area emitter must be nested in a <shape>");
    e.kind = EmitterKind::Area;
    e.shape = shape;
    e.radiance = props.getColor("radiance", Color(1.0f));
  } else if (type == "point") {
    e.kind = EmitterKind::Point;
    e.radiance = props.getColor("intensity", Color(1.0f));
    e.position = props.getTransform("to_world").point(props.getPoint("position", Vec3(0.0f)));
  } else if (type == "spot") {
    // Mitsuba's spot: at the origin of to_world, shining along its +z axis.
    e.kind = EmitterKind::Point;
    e.spot = true;
    e.radiance = props.getColor("intensity", Color(1.0f));
    const Transform toWorld = props.getTransform("to_world");
    e.position = toWorld.point(Vec3(0.0f));
    e.axis = normalize(toWorld.vector({0.0f, 0.0f, 1.0f}));
    const float cutoff = props.getFloat("cutoff_angle", 20.0f);
    const float beam = props.getFloat("beam_width", cutoff * 0.75f);
    if (!(cutoff > 0 && cutoff <= 180)) throw InputError(where, "spot cutoff_angle must be in (0, 180] degrees");
    if (!(beam > 0 && beam <= cutoff)) throw InputError(where, "spot beam_width must be in (0, cutoff_angle] degrees");
    if (!isFinite(e.axis)) throw InputError(where, "spot to_world has no direction (a zero scale?)");
    e.cutoffAngle = cutoff * kPi / 180;
    e.beamWidth = beam * kPi / 180;
  } else if (type == "directional") {
    // Light arriving from infinitely far along `direction` (or to_world's +z).
    e.kind = EmitterKind::Directional;
    e.radiance = props.getColor("irradiance", Color(1.0f));
    const Transform toWorld = props.getTransform("to_world");
    e.axis = normalize(toWorld.vector(props.getPoint("direction", Vec3(0.0f, 0.0f, 1.0f))));
    if (!isFinite(e.axis)) throw InputError(where, "directional light has no direction (zero vector or scale)");
  } else if (type == "constant") {
    e.kind = EmitterKind::Constant;
    e.radiance = props.getColor("radiance", Color(1.0f));
    if (scene_.environment()) throw InputError(where, "only one environment emitter is supported");
  } else if (type == "envmap") {
    if (scene_.environment()) throw InputError(where, "only one environment emitter is supported");
    e.kind = EmitterKind::Constant;
    e.map = environmentMap(doc, props, where);
    e.radiance = e.map->mean();
  } else if (type == "sky" || type == "sun" || type == "sunsky") {
    if (shape >= 0) throw InputError(where, "a " + type + " emitter cannot be attached to a shape");
    return daylight(type, props, where);
  } else {
    scene_.warnings.add(where, "emitter '" + type + "' is not supported; ignored");
    return -1;
  }
  if (shape >= 0 && type != "area") {
    scene_.warnings.add(where, "only area emitters can be attached to a shape; ignored");
    return -1;
  }
  if (e.radiance.x < 0 || e.radiance.y < 0 || e.radiance.z < 0)
    throw InputError(where, "emitted radiance must not be negative");
  props.find("sampling_weight");
  props.warnUnused(scene_.warnings);
  scene_.emitters.push_back(e);
  return int(scene_.emitters.size()) - 1;
}

}  // namespace erpt::xml

namespace erpt {

Scene loadScene(const std::string& path, const LoadOptions& options) {
  Scene scene;
  scene.file = path;
  xml::SceneBuilder builder(scene, options);
  builder.loadFile(path, 0);
  const SourceLocation sceneElement = builder.sceneElement();
  const std::string unused = builder.defines().unusedOverride();
  if (!unused.empty())
    throw UsageError("-D " + unused + "=" + options.defines.at(unused) + ": " + path + " has no parameter '" + unused +
                     "' (no <default name=\"" + unused + "\"> and no $" + unused + ")");
  for (const Material& m : scene.materials) scene.adjustsShadingFrames |= m.adjustsShadingFrame();
  // Instanced triangles take the primitive ids after the world's own, instance by instance.
  uint64_t next = scene.worldPrimitiveCount();
  for (size_t k = 0; k < scene.instances.count(); ++k) {
    scene.instances.firstPrimitive[k] = uint32_t(next);
    next += scene.instances.groupTriangleCount[scene.instances.group[k]];
    if (next >= 0xffff0000u)
      throw InputError(sceneElement, "the instances place more than 4 billion triangles (primitive ids are 32-bit)");
  }
  if (scene.primitiveCount() == 0 && scene.emitters.empty())
    throw InputError(sceneElement, "the scene has no geometry and no emitters");
  return scene;
}

bool Scene::opaqueAt(uint32_t triangle, float b1, float b2) const {
  const Material& m = materials[size_t(mesh.material[triangle])];
  if (!m.masked || mesh.emitter[triangle] >= 0) return true;
  Color opacity = m.opacity.value;
  if (m.opacity.texture >= 0) {
    const uint32_t a = mesh.v0[triangle], b = mesh.v1[triangle], c = mesh.v2[triangle];
    const float b0 = 1 - b1 - b2;
    opacity = textures[size_t(m.opacity.texture)].eval(b0 * mesh.u[a] + b1 * mesh.u[b] + b2 * mesh.u[c],
                                                       b0 * mesh.v[a] + b1 * mesh.v[b] + b2 * mesh.v[c]);
  }
  return (opacity.x + opacity.y + opacity.z) >= 1.5f;  // mean >= 0.5
}

bool Scene::hasMasks() const {
  for (const Material& m : materials)
    if (m.masked) return true;
  return false;
}

SurfaceColors Scene::surfaceColors(int material, float u, float v) const {
  auto resolve = [&](const ColorParam& p) { return p.texture < 0 ? p.value : textures[p.texture].eval(u, v); };
  return resolveSurfaceColors(materials[material], resolve);
}

const Emitter* Scene::environment() const {
  for (const Emitter& e : emitters)
    if (e.kind == EmitterKind::Constant) return &e;
  return nullptr;
}

}  // namespace erpt
