// The path contributions of docs/erpt-acceptance.md against independently measured Jacobians:
// a path's f in the caustic perturbation's measure must equal its f in the lens
// perturbation's measure times the Jacobian of the map from the caustic's parameters to the
// lens's, measured here by finite differences of that map traced with Embree. This checks
// density rules 3, 4 and 5 and the specular-chain step (refraction included) without the
// algebra of the derivation.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <optional>
#include <vector>

#include "models/bsdf.h"
#include "models/surface.h"
#include "support/erpt_world.h"
#include "support/test_support.h"

namespace erpt {
namespace {

using test::ErptWorld;

// Where the walk from the source s ends: film position of vertex 1 and the direction from
// vertex 1 towards vertex 2. The path leaves `from` along `dir` and follows the path's specular
// lobes; nullopt if the walk leaves the path's signature.
struct WalkEnd {
  double filmX, filmY;
  Vec3 towardsV2;
};
std::optional<WalkEnd> walkToVertex1(const ErptWorld& w, const PathVertex* path, int s, Vec3 from, Vec3 dir) {
  Vec3 origin = offsetOrigin(from, path[s].ng, dir);
  Vec3 previous = from;
  for (int j = s - 1; j >= 1; --j) {
    auto hit = w.traceOne(origin, dir);
    if (!hit) return std::nullopt;
    const Material& m = w.scene.materials[size_t(hit->material)];
    if (j == 1) {
      if (m.isPureSpecular()) return std::nullopt;
      float fx, fy;
      if (!w.camera->projectFrom(path[0].p, hit->position, fx, fy)) return std::nullopt;  // the pinhole or lens point
      return WalkEnd{double(fx), double(fy), normalize(previous - hit->position)};
    }
    Vec3 wo;
    if (!specularDirection(m, hit->shading.toLocal(-dir), reflectsAt(path, j), wo)) return std::nullopt;
    dir = hit->shading.toWorld(wo);
    origin = offsetOrigin(hit->position, hit->geometricNormal, dir);
    previous = hit->position;
  }
  return std::nullopt;
}

double determinant(double m[4][4], int n) {
  // Gaussian elimination with partial pivoting.
  double det = 1;
  for (int c = 0; c < n; ++c) {
    int p = c;
    for (int r = c + 1; r < n; ++r)
      if (std::abs(m[r][c]) > std::abs(m[p][c])) p = r;
    if (m[p][c] == 0) return 0;
    if (p != c) {
      for (int k = 0; k < n; ++k) std::swap(m[p][k], m[c][k]);
      det = -det;
    }
    det *= m[c][c];
    for (int r = c + 1; r < n; ++r) {
      const double f = m[r][c] / m[c][c];
      for (int k = c; k < n; ++k) m[r][k] -= f * m[c][k];
    }
  }
  return det;
}

// |det| of the map from the caustic's parameters to the lens's, by central differences.
// Without a specular chain (s = 2) both keep x_s fixed: the map is direction at s -> film
// position (2x2). With one, the lens regenerates x_s as well: the map is (point on the
// surface at s, direction at s) -> (film position, direction leaving vertex 1) (4x4).
// Directions are measured in the tangent plane of the path's own direction (solid angle to
// first order), points in the tangent plane of the surface (area).
std::optional<double> lensPerCausticMeasure(const ErptWorld& w, const PathVertex* path, int s, double h) {
  const Vec3 d0 = directionBetween(path[s], path[s - 1]);
  const Frame fd(d0), fs(path[s].ng);
  const bool chain = s > 2;
  const int n = chain ? 4 : 2;
  auto base = walkToVertex1(w, path, s, path[s].p, d0);
  if (!base) return std::nullopt;
  const Frame f1(base->towardsV2);
  auto outputs = [&](const double* p, double* out) {
    const Vec3 from = chain ? path[s].p + fs.s * float(p[2]) + fs.t * float(p[3]) : path[s].p;
    auto e = walkToVertex1(w, path, s, from, normalize(d0 + fd.s * float(p[0]) + fd.t * float(p[1])));
    if (!e) return false;
    out[0] = e->filmX;
    out[1] = e->filmY;
    out[2] = dot(e->towardsV2, f1.s);
    out[3] = dot(e->towardsV2, f1.t);
    return true;
  };
  double jac[4][4];
  for (int k = 0; k < n; ++k) {
    double p[4] = {0, 0, 0, 0}, plus[4], minus[4];
    p[k] = h;
    if (!outputs(p, plus)) return std::nullopt;
    p[k] = -h;
    if (!outputs(p, minus)) return std::nullopt;
    for (int r = 0; r < n; ++r) jac[r][k] = (plus[r] - minus[r]) / (2 * h);
  }
  return std::abs(determinant(jac, n));
}

// Runs the check on up to `wanted` seeds whose signature both mutations handle; `chain`
// selects paths with (true) or without (false) a specular chain between vertex 1 and s.
//
// What decides the outcome is the distribution of the relative differences, not one path: a
// finite-difference Jacobian of a badly conditioned path (grazing angles through glass, a
// facet edge of the tessellated spheres) can be off by 20% on one machine's rounding and not
// another's. A path is left out, by a stated criterion, when its Jacobian is not stable under
// halving the step (the map is not smooth there at this scale); the rest must agree in the
// median, the 90% quantile and the 95% quantile. A wrong density rule (rule 3's cosine, rule
// 5's cos^3) is off by 10-100x on every path, so every bound fails at once.
void checkCausticAgainstLens(const ErptWorld& w, bool chain, int wanted) {
  const MeasureContext mc = w.measure();
  PathVertex path[kMaxChainVertices];
  uint8_t kinds[kMaxChainVertices];
  int checked = 0, unstable = 0;
  double worst = 0;
  std::vector<double> errors;
  for (size_t i = 0; i < w.seeds.size() && checked < wanted; i += 7) {
    const int n = w.seedPath(i, path);
    if (n > kMaxChainVertices) continue;
    for (int j = 0; j < n; ++j) kinds[j] = path[j].kind;
    const int s = causticSource(kinds, n);
    // Both measures must agree beyond s: the lens must connect from s to the next vertex.
    if (s < 0 || (s > 2) != chain || (s + 1 < n && kinds[s + 1] == kSpecularVertex)) continue;
    const float fx = w.seeds.seeds.filmX[i], fy = w.seeds.seeds.filmY[i];
    const float lens = luminance(lensContribution(mc, path, n, fx, fy));
    const float caustic = luminance(causticContribution(mc, path, n, fx, fy));
    if (!(lens > 0) || !(caustic > 0)) continue;
    // Conditioning: the Jacobian at two step sizes must agree within 1%; otherwise the path is
    // close to a silhouette or facet edge and is left out (counted, printed).
    auto j1 = lensPerCausticMeasure(w, path, s, 2e-4), j2 = lensPerCausticMeasure(w, path, s, 1e-4);
    if (!j1 || !j2 || std::abs(*j1 / *j2 - 1) > 0.01) {
      ++unstable;
      continue;
    }
    const double ratio = double(caustic) / double(lens) / *j2;
    worst = std::max(worst, std::abs(ratio - 1));
    errors.push_back(std::abs(ratio - 1));
    ++checked;
  }
  std::sort(errors.begin(), errors.end());
  ASSERT_GE(checked, wanted / 2) << unstable << " paths left out as badly conditioned";
  const auto quantile = [&](double q) { return errors[std::min(errors.size() - 1, size_t(q * errors.size()))]; };
  const double median = quantile(0.5), p90 = quantile(0.9), p95 = quantile(0.95);
  std::printf("checked %d paths (%d left out: Jacobian unstable under halving the step): relative difference "
              "median %.4f, 90%% %.4f, 95%% %.4f, worst %.4f\n",
              checked, unstable, median, p90, p95, worst);
  EXPECT_LT(median, 0.01);
  EXPECT_LT(p90, 0.02);
  // The former per-path bound, now on the 95% quantile: single paths may be off by the finite
  // differences' error (faceted spheres with interpolated normals), most may not.
  EXPECT_LT(p95, 0.06);
}

TEST(ErptMeasure, CausticEqualsLensTimesJacobianWithoutSpecularChain) {
  ErptWorld w(test::sharedScenesDir() + "/cornell-box/scene.xml", 64, 1, FilterKind::Box);
  checkCausticAgainstLens(w, false, 40);
}

TEST(ErptMeasure, CausticEqualsLensTimesJacobianThroughGlassAndMirror) {
  ErptWorld w(test::sourceDir() + "/scenes/default/scene.xml", 64, 4, FilterKind::Box);
  checkCausticAgainstLens(w, true, 100);
}

// Through a thin lens (radius 0.3, focused 5.8 away, in front of the spheres): each path keeps
// its lens point, the lens measure is the film position of rays from it, the caustic's eye
// connection projects through it. The Jacobian of the caustic's parameters to the film
// position, measured here, must match cos^3 / plane distance^2 of the lens ray's own angle.
TEST(ErptMeasure, CausticEqualsLensTimesJacobianThroughAThinLens) {
  ErptWorld w(test::sourceDir() + "/scenes/default/scene.xml", 64, 4, FilterKind::Box, 1, {0.3f, 5.8f});
  checkCausticAgainstLens(w, true, 100);
}

}  // namespace
}  // namespace erpt
