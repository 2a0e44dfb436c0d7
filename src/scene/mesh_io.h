// Readers for mesh files and generators for Mitsuba's built-in shapes. They return meshes in
// object space; the scene loader transforms them, validates them and appends them to the
// scene's triangle soup. Readers throw InputError on malformed input: at the line for text
// (OBJ, PLY headers and ascii bodies), at line 0 with a byte offset or triangle for binary
// data, which the scene loader then reports at the XML line naming the file.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "erpt/error.h"
#include "erpt/math.h"

namespace erpt {

struct MeshData {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;    // empty, or one per position
  std::vector<float> uvs;       // empty, or two per position
  std::vector<uint32_t> indices;  // three per triangle
};

// Wavefront OBJ (polygons are fan-triangulated). `flipV` turns v into 1 - v (Mitsuba 0.6
// does this for OBJ files by default).
MeshData readObj(const std::string& path, bool flipV, Warnings& warnings);
// Stanford PLY, ascii and binary (little and big endian); vertex x/y/z, optional
// nx/ny/nz and u/v (or s/t, texture_u/texture_v); faces as `vertex_indices` or `vertex_index` lists.
MeshData readPly(const std::string& path, Warnings& warnings);
// Mitsuba's .serialized format (zlib-compressed, versions 3 and 4), shape `shapeIndex`.
MeshData readSerialized(const std::string& path, int shapeIndex, Warnings& warnings);

MeshData makeRectangle();  // [-1,1]^2 at z = 0, normal +z
MeshData makeCube();       // [-1,1]^3, outward normals
MeshData makeDisk(int segments = 256);  // unit disk at z = 0, normal +z
MeshData makeSphere(Vec3 center, float radius, int rings = 256, int segments = 512);
// Mitsuba's open cylinder (no caps) from p0 to p1: exact radial normals, u = azimuth / 2 pi,
// v = position along the axis (0 at p0, 1 at p1); 1024 segments around.
MeshData makeCylinder(Vec3 p0, Vec3 p1, float radius, int segments = 1024);

}  // namespace erpt
