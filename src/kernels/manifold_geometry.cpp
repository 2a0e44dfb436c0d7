// The generalised geometry term of a specular chain (docs/manifold.md, "The generalised
// geometry term"): how the direction leaving x_0 changes as the endpoint x_n moves on its
// surface, with the specular vertices kept on the manifold by the tangent-move solve.
#include <cmath>

#include "kernels/manifold_walk.h"

namespace erpt {

namespace {
double norm(DVec3 a) { return std::sqrt(dot(a, a)); }
DVec3 unit(DVec3 a) { return a * (1.0 / norm(a)); }
}  // namespace

double generalizedGeometry(const ManifoldChain& chain) {
  const size_t n = chain.size() - 1;
  if (n < 1) return 0;
  const ManifoldVertex &x0 = chain[0], &xn = chain[n];
  const DVec3 d = chain[1].p - x0.p;
  const double r = norm(d);
  const DVec3 w = d * (1.0 / r);
  // d x_1 / d (u_n, v_n): the endpoint itself when no specular vertex lies between.
  DVec3 dx1[2];
  if (n == 1) {
    dx1[0] = xn.dpdu, dx1[1] = xn.dpdv;
  } else {
    double movesU[2 * kMaxManifoldVertices], movesV[2 * kMaxManifoldVertices];
    const double unitMoves[2][2] = {{1, 0}, {0, 1}};
    double* const moves[2] = {movesU, movesV};
    if (!manifoldTangentMoves(chain, 2, unitMoves, moves)) return 0;
    dx1[0] = chain[1].dpdu * movesU[0] + chain[1].dpdv * movesU[1];
    dx1[1] = chain[1].dpdu * movesV[0] + chain[1].dpdv * movesV[1];
  }
  // d omega_0 = (I - w w^T) d x_1 / r, in an orthonormal basis (a, b) of w's tangent plane.
  const DVec3 helper = std::abs(w.x) < 0.9 ? DVec3{1, 0, 0} : DVec3{0, 1, 0};
  const DVec3 a = unit(cross(helper, w)), b = cross(w, a);
  const double j00 = dot(dx1[0], a) / r, j01 = dot(dx1[1], a) / r, j10 = dot(dx1[0], b) / r, j11 = dot(dx1[1], b) / r;
  const double solidAnglePerUv = std::abs(j00 * j11 - j01 * j10);
  const double areaPerUv = norm(cross(xn.dpdu, xn.dpdv));
  if (!(areaPerUv > 0)) return 0;
  return std::abs(dot(w, x0.n)) * solidAnglePerUv / areaPerUv;
}

}  // namespace erpt
