// The manifold walk (kernels/manifold_walk.h) on surfaces whose answers are known in closed
// form: a flat mirror (the mirror-image construction), a flat water surface and a glass slab
// (Snell's law; a slab leaves directions parallel), mirror and glass spheres (their curvature
// enters the Jacobian). The surfaces are analytic, traced here in double precision.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "kernels/manifold_walk.h"

namespace erpt {
namespace {

double norm(DVec3 a) { return std::sqrt(dot(a, a)); }
DVec3 unit(DVec3 a) { return a * (1.0 / norm(a)); }

// Two unit tangents of a unit normal.
void tangents(DVec3 n, DVec3& s, DVec3& t) {
  const DVec3 helper = std::abs(n.x) < 0.9 ? DVec3{1, 0, 0} : DVec3{0, 1, 0};
  s = unit(cross(helper, n));
  t = cross(n, s);
}

struct Surface {
  bool sphere = false;
  DVec3 point;   // a point of the plane, or the sphere's centre
  DVec3 normal;  // the plane's (its exterior side)
  double radius = 0;
  double eta = 1;  // the interior's index of refraction (the normal points out of it)
  uint32_t id = 0;
};

class AnalyticTracer final : public ManifoldTracer {
 public:
  explicit AnalyticTracer(std::vector<Surface> surfaces) : surfaces_(std::move(surfaces)) {}
  bool intersect(DVec3 o, DVec3 d, ManifoldVertex& hit) const override {
    double best = 1e30;
    const Surface* found = nullptr;
    for (const Surface& s : surfaces_) {
      double t = -1;
      if (!s.sphere) {
        const double den = dot(d, s.normal);
        if (std::abs(den) > 1e-15) t = dot(s.point - o, s.normal) / den;
      } else {
        const DVec3 oc = o - s.point;
        const double b = dot(oc, d), c = dot(oc, oc) - s.radius * s.radius, disc = b * b - c;
        if (disc >= 0) {
          const double r = std::sqrt(disc);
          t = -b - r > 1e-9 ? -b - r : -b + r;
        }
      }
      if (t > 1e-9 && t < best) best = t, found = &s;
    }
    if (!found) return false;
    hit = ManifoldVertex{};
    hit.p = o + d * best;
    hit.n = found->sphere ? unit(hit.p - found->point) : found->normal;
    tangents(hit.n, hit.dpdu, hit.dpdv);
    if (found->sphere) {  // n = (p - c) / r: it turns by dp / r
      hit.dndu = hit.dpdu * (1.0 / found->radius);
      hit.dndv = hit.dpdv * (1.0 / found->radius);
    }
    hit.eta = found->eta;
    hit.surface = found->id;
    return true;
  }

 private:
  std::vector<Surface> surfaces_;
};

// The chain from `origin` along `direction` through surfaces that `reflects` says reflect (or
// refract), ending on the surface after them.
ManifoldChain traceChain(const AnalyticTracer& tracer, DVec3 origin, DVec3 direction,
                                       std::vector<uint32_t> surfaces, std::vector<bool> reflects) {
  ManifoldChain shape(surfaces.size() + 1);
  shape[0].p = origin;
  shape[0].surface = 1000;
  for (size_t j = 0; j < surfaces.size(); ++j) {
    shape[j + 1].surface = surfaces[j];
    shape[j + 1].reflect = j < reflects.size() ? bool(reflects[j]) : true;
  }
  ManifoldChain chain;
  EXPECT_TRUE(retraceChain(tracer, shape, direction, chain));
  return chain;
}

void expectOnManifold(const ManifoldChain& chain) {
  for (int i = 1; i + 1 < int(chain.size()); ++i) {
    double c[2];
    manifoldConstraint(chain, i, c);
    EXPECT_NEAR(c[0], 0, 1e-9) << i;
    EXPECT_NEAR(c[1], 0, 1e-9) << i;
  }
}

Surface plane(DVec3 point, DVec3 normal, uint32_t id, double eta = 1) {
  Surface s;
  s.point = point, s.normal = normal, s.id = id, s.eta = eta;
  return s;
}
Surface sphere(DVec3 centre, double radius, uint32_t id, double eta = 1) {
  Surface s;
  s.sphere = true, s.point = centre, s.radius = radius, s.id = id, s.eta = eta;
  return s;
}

TEST(ManifoldWalk, ConstraintsVanishOnReflectedAndRefractedPaths) {
  const AnalyticTracer mirror({plane({0, 0, 0}, {0, 1, 0}, 1), plane({3, 0, 0}, {-1, 0, 0}, 2)});
  expectOnManifold(traceChain(mirror, {0, 1, 0.2}, {1, -0.7, 0.1}, {1, 2}, {true}));
  const AnalyticTracer water({plane({0, 0, 0}, {0, 1, 0}, 1, 1.33), plane({0, -1, 0}, {0, 1, 0}, 2)});
  const auto chain = traceChain(water, {0, 1, 0}, {0.6, -1, 0.2}, {1, 2}, {false});
  expectOnManifold(chain);
  // And off the manifold they do not: a refracted path's constraint with a mirror's rule.
  ManifoldChain wrong = chain;
  wrong[1].eta = 1.0;
  double c[2];
  manifoldConstraint(wrong, 1, c);
  EXPECT_GT(std::hypot(c[0], c[1]), 0.05);
}

// The Jacobian blocks against central differences of the constraint, on a chain through a
// glass sphere (two refractions, curved: the normal turns with the vertex) onto a floor.
TEST(ManifoldWalk, ConstraintBlocksAreTheConstraintsDerivatives) {
  const AnalyticTracer scene({sphere({0, 0, 0}, 1, 1, 1.5), plane({0, -3, 0}, {0, 1, 0}, 2)});
  const auto chain = traceChain(scene, {0.3, 3, 0.1}, {-0.05, -1, 0.02}, {1, 1, 2}, {false, false});
  ASSERT_EQ(chain.size(), 4u);
  // A point a little off the manifold, so that no derivative is zero by symmetry.
  ManifoldChain at = chain;
  at[2].p = at[2].p + at[2].dpdu * 0.01;
  const double h = 1e-6;
  for (int i = 1; i <= 2; ++i) {
    double blocks[3][4];
    manifoldConstraintBlocks(at, i, blocks[0], blocks[1], blocks[2]);
    for (int which = 0; which < 3; ++which) {
      for (int axis = 0; axis < 2; ++axis) {
        auto movedBy = [&](double e) {
          ManifoldChain m = at;
          ManifoldVertex& v = m[size_t(i - 1 + which)];
          v.p = v.p + (axis == 0 ? v.dpdu : v.dpdv) * e;
          v.n = unit(v.n + (axis == 0 ? v.dndu : v.dndv) * e);
          double c[2];
          manifoldConstraint(m, i, c);
          return std::pair{c[0], c[1]};
        };
        const auto plus = movedBy(h), minus = movedBy(-h);
        EXPECT_NEAR(blocks[which][axis], (plus.first - minus.first) / (2 * h), 1e-6) << i << which << axis;
        EXPECT_NEAR(blocks[which][2 + axis], (plus.second - minus.second) / (2 * h), 1e-6) << i << which << axis;
      }
    }
  }
}

// A flat mirror: the reflection point is where the line from the origin's mirror image to the
// endpoint crosses the mirror.
TEST(ManifoldWalk, FlatMirrorReachesTheMirrorImageConstruction) {
  const AnalyticTracer scene({plane({0, 0, 0}, {0, 1, 0}, 1), plane({3, 0, 0}, {-1, 0, 0}, 2)});
  const DVec3 origin{0, 1, 0.2};
  auto chain = traceChain(scene, origin, {1, -0.7, 0.1}, {1, 2}, {true});
  const DVec3 target = chain[2].p + DVec3{0, 0.4, -0.3};  // on the wall x = 3
  const ManifoldWalkResult r = manifoldWalk(scene, chain, target, 1e-10);
  ASSERT_TRUE(r.converged) << r.distance;
  EXPECT_LE(r.iterations, 10);  // Newton's convergence (measured: 4 steps to 1e-10)
  const DVec3 image{origin.x, -origin.y, origin.z};
  const double s = image.y / (image.y - target.y);  // where image + s (target - image) has y = 0
  const DVec3 expected = image + (target - image) * s;
  EXPECT_NEAR(norm(chain[1].p - expected), 0, 1e-9);
  expectOnManifold(chain);
}

// Water: the endpoint moves on the pool's floor; the refraction point obeys Snell's law.
TEST(ManifoldWalk, FlatWaterSurfaceObeysSnellsLaw) {
  const double eta = 1.33;
  const AnalyticTracer scene({plane({0, 0, 0}, {0, 1, 0}, 1, eta), plane({0, -1, 0}, {0, 1, 0}, 2)});
  auto chain = traceChain(scene, {0, 1, 0}, {0.3, -1, 0.1}, {1, 2}, {false});
  for (const DVec3 move : {DVec3{0.5, 0, 0.2}, DVec3{-0.8, 0, 0.6}}) {
    const DVec3 target = chain[2].p + move;
    const ManifoldWalkResult r = manifoldWalk(scene, chain, target, 1e-10);
    ASSERT_TRUE(r.converged) << r.distance;
    EXPECT_LE(r.iterations, 15);
    const DVec3 in = unit(chain[1].p - chain[0].p), out = unit(chain[2].p - chain[1].p);
    // Tangential components: sin(theta_1) = eta sin(theta_2), in the same plane.
    EXPECT_NEAR(in.x, eta * out.x, 1e-9);
    EXPECT_NEAR(in.z, eta * out.z, 1e-9);
    EXPECT_NEAR(norm(chain[2].p - target), 0, 1e-10);
  }
}

// A glass slab (two parallel interfaces, the lower one's exterior below it): the ray leaves
// parallel to the way it came in, so the endpoint's direction from the exit point is the
// direction from the origin to the entry point.
TEST(ManifoldWalk, GlassSlabLeavesDirectionsParallel) {
  const AnalyticTracer scene({plane({0, 0, 0}, {0, 1, 0}, 1, 1.5), plane({0, -0.5, 0}, {0, -1, 0}, 2, 1.5),
                              plane({0, -2, 0}, {0, 1, 0}, 3)});
  auto chain = traceChain(scene, {0, 1, 0}, {0.2, -1, -0.1}, {1, 2, 3}, {false, false});
  const DVec3 target = chain[3].p + DVec3{0.7, 0, -0.4};
  const ManifoldWalkResult r = manifoldWalk(scene, chain, target, 1e-10);
  ASSERT_TRUE(r.converged) << r.distance;
  const DVec3 in = unit(chain[1].p - chain[0].p), out = unit(chain[3].p - chain[2].p);
  EXPECT_NEAR(norm(in - out), 0, 1e-9);
  expectOnManifold(chain);
}

// A convex mirror sphere and a glass sphere: curved chains, whose Jacobians carry the
// curvature. The walk reaches its targets; the vertices stay on the spheres and obey the laws.
TEST(ManifoldWalk, SpheresReachTheirTargets) {
  {
    // Seen from x = 3, the sphere reflects onto a wall behind the viewer.
    const AnalyticTracer scene({sphere({0, 0, 0}, 1, 1), plane({6, 0, 0}, {-1, 0, 0}, 2)});
    auto chain = traceChain(scene, {3, 0.2, 0.1}, {-1, 0.15, 0.05}, {1, 2}, {true});
    const DVec3 target = chain[2].p + DVec3{0, 0.6, -0.5};
    const ManifoldWalkResult r = manifoldWalk(scene, chain, target, 1e-9);
    ASSERT_TRUE(r.converged) << r.distance;
    EXPECT_NEAR(norm(chain[1].p), 1.0, 1e-12);
    const DVec3 n = chain[1].p, wi = unit(chain[0].p - chain[1].p), wo = unit(chain[2].p - chain[1].p);
    EXPECT_NEAR(dot(wi, n), dot(wo, n), 1e-9);  // equal angles
    expectOnManifold(chain);
  }
  {
    const AnalyticTracer scene({sphere({0, 0, 0}, 1, 1, 1.5), plane({0, -3, 0}, {0, 1, 0}, 2)});
    auto chain = traceChain(scene, {0.3, 3, 0.1}, {-0.05, -1, 0.02}, {1, 1, 2}, {false, false});
    const DVec3 target = chain[3].p + DVec3{0.3, 0, 0.2};
    const ManifoldWalkResult r = manifoldWalk(scene, chain, target, 1e-9);
    ASSERT_TRUE(r.converged) << r.distance;
    EXPECT_LE(r.iterations, 20);
    expectOnManifold(chain);
  }
}

// A target the chain cannot reach (on the wall below the mirror's plane, where no reflected
// ray goes) ends unconverged and closer, never off the manifold.
TEST(ManifoldWalk, AnUnreachableTargetIsReportedNotFaked) {
  const AnalyticTracer scene({plane({0, 0, 0}, {0, 1, 0}, 1), plane({3, 0, 0}, {-1, 0, 0}, 2)});
  auto chain = traceChain(scene, {0, 1, 0.2}, {1, -0.7, 0.1}, {1, 2}, {true});
  const DVec3 start = chain[2].p;
  const DVec3 target{3, -1, 0.3};
  const ManifoldWalkResult r = manifoldWalk(scene, chain, target, 1e-9, 40);
  EXPECT_FALSE(r.converged);
  EXPECT_LT(r.distance, norm(start - target));
  EXPECT_GE(r.distance, 1.0);
  expectOnManifold(chain);
}

// The generalised geometry term without specular vertices is the usual one, and through a
// flat mirror it is the unfolded path's: cos cos / (total length)^2.
TEST(ManifoldGeometry, PlainSegmentAndFlatMirrorHaveTheirClosedForms) {
  const AnalyticTracer wall({plane({3, 0, 0}, {-1, 0, 0}, 2)});
  auto segment = traceChain(wall, {0, 1, 0.2}, {1, -0.3, 0.1}, {2}, {});
  segment[0].n = unit(DVec3{1, 0.2, 0});
  {
    const DVec3 d = segment[1].p - segment[0].p;
    const double r2 = dot(d, d), cos0 = dot(unit(d), segment[0].n), cos1 = -dot(unit(d), segment[1].n);
    EXPECT_NEAR(generalizedGeometry(segment) / (cos0 * cos1 / r2), 1.0, 1e-12);
  }
  const AnalyticTracer scene({plane({0, 0, 0}, {0, 1, 0}, 1), plane({3, 0, 0}, {-1, 0, 0}, 2)});
  auto chain = traceChain(scene, {0, 1, 0.2}, {1, -0.7, 0.1}, {1, 2}, {true});
  chain[0].n = unit(DVec3{1, -0.5, 0});
  const DVec3 first = chain[1].p - chain[0].p, second = chain[2].p - chain[1].p;
  const double length = std::sqrt(dot(first, first)) + std::sqrt(dot(second, second));
  const double cos0 = dot(unit(first), chain[0].n), cosN = -dot(unit(second), chain[2].n);
  EXPECT_NEAR(generalizedGeometry(chain) / (cos0 * cosN / (length * length)), 1.0, 1e-9);
}

// Curved and refracting chains: the term against the walk itself. The endpoint is moved by
// +-h along its two (orthonormal) tangents and walked there exactly; the change of the
// direction leaving x_0 gives d omega / dA by central differences.
TEST(ManifoldGeometry, CurvedAndRefractingChainsMatchTheWalksDifferences) {
  struct Case {
    std::vector<Surface> surfaces;
    DVec3 origin, direction;
    std::vector<uint32_t> ids;
    std::vector<bool> reflects;
  };
  const std::vector<Case> cases = {
      {{sphere({0, 0, 0}, 1, 1), plane({6, 0, 0}, {-1, 0, 0}, 2)}, {3, 0.2, 0.1}, {-1, 0.15, 0.05}, {1, 2}, {true}},
      {{plane({0, 0, 0}, {0, 1, 0}, 1, 1.33), plane({0, -1, 0}, {0, 1, 0}, 2)}, {0, 1, 0}, {0.3, -1, 0.1}, {1, 2}, {false}},
      {{sphere({0, 0, 0}, 1, 1, 1.5), plane({0, -3, 0}, {0, 1, 0}, 2)}, {0.3, 3, 0.1}, {-0.05, -1, 0.02}, {1, 1, 2},
       {false, false}},
  };
  for (size_t k = 0; k < cases.size(); ++k) {
    const Case& c = cases[k];
    const AnalyticTracer scene(c.surfaces);
    auto chain = traceChain(scene, c.origin, c.direction, c.ids, c.reflects);
    chain[0].n = unit(c.direction);
    const double analytic = generalizedGeometry(chain);
    const double h = 1e-5;
    DVec3 dw[2];
    for (int axis = 0; axis < 2; ++axis) {
      DVec3 w[2];
      for (int side = 0; side < 2; ++side) {
        auto moved = chain;
        const ManifoldVertex& end = chain.back();
        const DVec3 target = end.p + (axis == 0 ? end.dpdu : end.dpdv) * (side == 0 ? h : -h);
        ASSERT_TRUE(manifoldWalk(scene, moved, target, 1e-11).converged) << k;
        w[side] = unit(moved[1].p - moved[0].p);
      }
      dw[axis] = (w[0] - w[1]) * (1 / (2 * h));
    }
    const DVec3 w0 = unit(chain[1].p - chain[0].p);
    const double numeric = std::abs(dot(w0, chain[0].n)) * norm(cross(dw[0], dw[1]));
    EXPECT_NEAR(analytic / numeric, 1.0, 1e-4) << k;
    // The term does not depend on how the vertices' tangents are scaled or skewed (a mesh's
    // edges are neither unit nor orthogonal).
    auto skewed = chain;
    for (size_t j = 1; j < skewed.size(); ++j) {
      ManifoldVertex& v = skewed[j];
      v.dpdv = v.dpdv + v.dpdu * 0.5, v.dndv = v.dndv + v.dndu * 0.5;
      v.dpdu = v.dpdu * 2.0, v.dndu = v.dndu * 2.0;
    }
    EXPECT_NEAR(generalizedGeometry(skewed) / analytic, 1.0, 1e-9) << k;
  }
}

}  // namespace
}  // namespace erpt
