// Mitsuba's analytic shapes as triangle meshes in object space. The sphere (when not exact,
// see docs/exact-spheres.md) and the cylinder are tessellated finely and carry exact
// normals, so neither silhouettes nor shading show facets.
#include "scene/mesh_io.h"

namespace erpt {

MeshData makeRectangle() {
  MeshData m;
  m.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  m.normals.assign(4, Vec3(0, 0, 1));
  m.uvs = {0, 0, 1, 0, 1, 1, 0, 1};
  m.indices = {0, 1, 2, 2, 3, 0};
  return m;
}

MeshData makeCube() {
  MeshData m;
  // For each axis and sign, a face with outward normal; corners listed counter-clockwise
  // as seen from outside.
  for (int axis = 0; axis < 3; ++axis)
    for (int sign = -1; sign <= 1; sign += 2) {
      int a = (axis + 1) % 3, b = (axis + 2) % 3;
      if (sign < 0) std::swap(a, b);
      Vec3 n(0.0f);
      n[axis] = float(sign);
      uint32_t base = uint32_t(m.positions.size());
      const float corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
      for (auto& c : corners) {
        Vec3 p(0.0f);
        p[axis] = float(sign);
        p[a] = c[0];
        p[b] = c[1];
        m.positions.push_back(p);
        m.normals.push_back(n);
        m.uvs.push_back((c[0] + 1) / 2);
        m.uvs.push_back((c[1] + 1) / 2);
      }
      for (uint32_t i : {0u, 1u, 2u, 2u, 3u, 0u}) m.indices.push_back(base + i);
    }
  return m;
}

MeshData makeDisk(int segments) {
  MeshData m;
  m.positions.push_back({0, 0, 0});
  m.uvs.insert(m.uvs.end(), {0.5f, 0.5f});
  for (int i = 0; i < segments; ++i) {
    float phi = 2 * kPi * i / segments;
    m.positions.push_back({std::cos(phi), std::sin(phi), 0});
    m.uvs.push_back(0.5f + 0.5f * std::cos(phi));
    m.uvs.push_back(0.5f + 0.5f * std::sin(phi));
  }
  m.normals.assign(m.positions.size(), Vec3(0, 0, 1));
  for (int i = 0; i < segments; ++i) {
    m.indices.push_back(0);
    m.indices.push_back(1 + i);
    m.indices.push_back(1 + (i + 1) % segments);
  }
  return m;
}

MeshData makeSphere(Vec3 center, float radius, int rings, int segments) {
  MeshData m;
  for (int r = 0; r <= rings; ++r) {
    float theta = kPi * r / rings;
    for (int s = 0; s <= segments; ++s) {
      float phi = 2 * kPi * s / segments;
      Vec3 n{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
      m.positions.push_back(center + n * radius);
      m.normals.push_back(n);
      m.uvs.push_back(float(s) / segments);
      m.uvs.push_back(float(r) / rings);  // Mitsuba 0.6: v = theta / pi, as the exact sphere
    }
  }
  auto id = [&](int r, int s) { return uint32_t(r * (segments + 1) + s); };
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      // Skip the zero-area triangles at the poles.
      if (r != 0) m.indices.insert(m.indices.end(), {id(r, s), id(r + 1, s), id(r, s + 1)});
      if (r != rings - 1) m.indices.insert(m.indices.end(), {id(r, s + 1), id(r + 1, s), id(r + 1, s + 1)});
    }
  return m;
}

MeshData makeCylinder(Vec3 p0, Vec3 p1, float radius, int segments) {
  MeshData m;
  const Vec3 axis = p1 - p0;
  const Frame frame(normalize(axis));
  for (int s = 0; s <= segments; ++s) {
    const float phi = 2 * kPi * float(s) / float(segments);
    const Vec3 n = frame.toWorld({std::cos(phi), std::sin(phi), 0.0f});
    for (int end = 0; end < 2; ++end) {
      m.positions.push_back((end == 0 ? p0 : p1) + n * radius);
      m.normals.push_back(n);
      m.uvs.push_back(float(s) / float(segments));
      m.uvs.push_back(float(end));
    }
  }
  for (int s = 0; s < segments; ++s) {
    const uint32_t a = uint32_t(2 * s), b = a + 1, c = a + 2, d = a + 3;  // (p0, p1) at s and s + 1
    m.indices.insert(m.indices.end(), {a, c, b, b, c, d});
  }
  return m;
}

}  // namespace erpt
