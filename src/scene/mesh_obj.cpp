// OBJ files through tinyobjloader. OBJ indexes positions, normals and uvs separately, so
// every distinct (position, normal, uv) triple becomes one output vertex.
#include <cmath>
#include <map>
#include <optional>
#include <tuple>

#include <tiny_obj_loader.h>

#include "io/file_util.h"
#include "scene/mesh_io.h"
#include "obj_statements.h"

namespace erpt {

namespace {
// tinyobjloader's warnings can run over several lines; the first says what it is.
std::string firstLine(const std::string& s) {
  auto end = s.find('\n');
  return end == std::string::npos ? s : s.substr(0, end);
}

// A face refers to something the file does not define: the statement that does, at its line.
[[noreturn]] void throwBadFaceReference(const std::string& path, const std::string& cause) {
  if (std::optional<InputError> found = obj::badFaceReference(path)) throw *found;
  throw InputError({path, 0}, cause);  // not found again: the scene loader names the file
}
}  // namespace

MeshData readObj(const std::string& path, bool flipV, Warnings& warnings) {
  requireReadableFile(path, "mesh file");
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path, config))
    throw obj::parseFailure(path, reader.Error());
  // tinyobjloader drops a polygon of four or more corners with a vertex index out of range,
  // with only a warning; a triangle like it is an error below, and so is the polygon.
  const std::string& warning = reader.Warning();
  if (warning.find("out of bounds") != std::string::npos || warning.find("invalid vertex index") != std::string::npos)
    if (std::optional<InputError> found = obj::badFaceReference(path)) throw *found;
  if (!warning.empty()) warnings.add({path, 0}, firstLine(warning));

  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  for (size_t i = 0; i < attrib.vertices.size(); ++i)
    if (!std::isfinite(attrib.vertices[i]))
      throw InputError({path, obj::lineOfVertex(path, i / 3)}, "non-finite vertex position");
  MeshData mesh;
  std::map<std::tuple<int, int, int>, uint32_t> remap;
  bool anyNormals = !attrib.normals.empty(), anyUvs = !attrib.texcoords.empty();
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    for (const tinyobj::index_t& idx : shape.mesh.indices) {
      auto key = std::make_tuple(idx.vertex_index, idx.normal_index, idx.texcoord_index);
      auto found = remap.find(key);
      if (found != remap.end()) {
        mesh.indices.push_back(found->second);
        continue;
      }
      if (idx.vertex_index < 0 || size_t(idx.vertex_index) * 3 + 2 >= attrib.vertices.size())
        throwBadFaceReference(path, "face refers to a vertex that does not exist");
      // (tinyobjloader leaves normal and uv indices unchecked; found by tests/fuzz.)
      if (idx.normal_index >= 0 && size_t(idx.normal_index) * 3 + 2 >= attrib.normals.size())
        throwBadFaceReference(path, "face refers to a normal that does not exist");
      if (idx.texcoord_index >= 0 && size_t(idx.texcoord_index) * 2 + 1 >= attrib.texcoords.size())
        throwBadFaceReference(path, "face refers to a texture coordinate that does not exist");
      uint32_t id = uint32_t(mesh.positions.size());
      remap.emplace(key, id);
      mesh.indices.push_back(id);
      const float* p = &attrib.vertices[size_t(idx.vertex_index) * 3];
      mesh.positions.push_back({p[0], p[1], p[2]});
      if (anyNormals) {
        Vec3 n(0.0f);
        if (idx.normal_index >= 0) {
          const float* q = &attrib.normals[size_t(idx.normal_index) * 3];
          n = {q[0], q[1], q[2]};
        }
        mesh.normals.push_back(n);
      }
      if (anyUvs) {
        float u = 0, v = 0;
        if (idx.texcoord_index >= 0) {
          u = attrib.texcoords[size_t(idx.texcoord_index) * 2];
          v = attrib.texcoords[size_t(idx.texcoord_index) * 2 + 1];
        }
        mesh.uvs.push_back(u);
        mesh.uvs.push_back(flipV ? 1.0f - v : v);
      }
    }
  }
  // A vertex without a normal would poison interpolation: fall back to face normals.
  for (const Vec3& n : mesh.normals)
    if (n.x == 0 && n.y == 0 && n.z == 0) {
      mesh.normals.clear();
      warnings.add({path, 0}, "some vertices have no normal; using face normals for the whole mesh");
      break;
    }
  return mesh;
}

}  // namespace erpt
