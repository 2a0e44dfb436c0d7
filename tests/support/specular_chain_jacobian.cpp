#include "support/specular_chain_jacobian.h"

#include <cmath>

#include "models/bsdf.h"
#include "models/surface.h"

namespace erpt::test {

namespace {

// Where the ray from vertex b along `dir` lands on c's surface after the path's specular lobes.
std::optional<Vec3> landing(const ErptWorld& w, const PathVertex* path, int b, int c, Vec3 dir) {
  Vec3 origin = offsetOrigin(path[b].p, path[b].ng, dir);
  for (int j = b + 1; j <= c; ++j) {
    auto hit = w.traceOne(origin, dir);
    if (!hit) return std::nullopt;
    if (j == c) return hit->position;
    const Material& m = w.scene.materials[size_t(hit->material)];
    Vec3 wo;
    if (!specularDirection(m, hit->shading.toLocal(-dir), reflectsAt(path, j), wo)) return std::nullopt;
    dir = hit->shading.toWorld(wo);
    origin = offsetOrigin(hit->position, hit->geometricNormal, dir);
  }
  return std::nullopt;
}

}  // namespace

std::optional<double> solidAnglePerAreaByDifferences(const ErptWorld& w, const PathVertex* path, int b, int c, double h) {
  const Vec3 d0 = normalize(path[b + 1].p - path[b].p);
  const Frame fd(d0), fc(path[c].ng);
  double jac[2][2];
  for (int k = 0; k < 2; ++k) {
    const Vec3 axis = k == 0 ? fd.s : fd.t;
    auto plus = landing(w, path, b, c, normalize(d0 + axis * float(h)));
    auto minus = landing(w, path, b, c, normalize(d0 - axis * float(h)));
    if (!plus || !minus) return std::nullopt;
    const Vec3 d = *plus - *minus;
    jac[0][k] = double(dot(d, fc.s)) / (2 * h);
    jac[1][k] = double(dot(d, fc.t)) / (2 * h);
  }
  const double areaPerSolidAngle = std::abs(jac[0][0] * jac[1][1] - jac[0][1] * jac[1][0]);
  if (!(areaPerSolidAngle > 0)) return std::nullopt;
  return 1 / areaPerSolidAngle;
}

std::optional<double> stableSolidAnglePerArea(const ErptWorld& w, const PathVertex* path, int b, int c,
                                              double agreement) {
  auto j1 = solidAnglePerAreaByDifferences(w, path, b, c, 2e-4), j2 = solidAnglePerAreaByDifferences(w, path, b, c, 1e-4);
  if (!j1 || !j2 || std::abs(*j1 / *j2 - 1) > agreement) return std::nullopt;
  return j2;
}

}  // namespace erpt::test
