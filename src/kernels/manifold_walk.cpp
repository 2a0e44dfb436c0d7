#include "kernels/manifold_walk.h"

#include <algorithm>
#include <cmath>

namespace erpt {

namespace {

double norm(DVec3 a) { return std::sqrt(dot(a, a)); }
DVec3 unit(DVec3 a) { return a * (1.0 / norm(a)); }

// The index of refraction on direction w's side of vertex v's surface.
double iorOnSide(const ManifoldVertex& v, DVec3 w) { return dot(w, v.n) >= 0 ? 1.0 : v.eta; }

// The derivative of normalize(v) along dv, with u = v / |v| and len = |v|: dv's part
// perpendicular to u, over len.
DVec3 normalizedAlong(DVec3 u, double len, DVec3 dv) { return (dv - u * dot(u, dv)) * (1.0 / len); }

// Constraint i's value and its 2x2 blocks (rows: the constraint's two components; columns: the
// moves along dpdu, dpdv) for moves of x_{i-1} (a), x_i (b) and x_{i+1} (c), by the chain rule
// through the normalisations (checked against central differences by the tests). With
// wi, wo the unit directions to the neighbours, h = normalize(eta_in wi + eta_out wo) and the
// tangent frame s = normalize(dpdu - n (n . dpdu)), t = n x s of the vertex's normal n:
// c = (h . s, h . t). A neighbour's move turns wi or wo only; the vertex's own move turns both
// and its normal (its curvature: dndu, dndv), and with the normal its frame.
void constraintAndBlocks(const ManifoldChain& chain, int i, double value[2], double* a, double* b, double* c) {
  const ManifoldVertex &prev = chain[size_t(i - 1)], &cur = chain[size_t(i)], &next = chain[size_t(i + 1)];
  const double nLen = norm(cur.n);
  const DVec3 n = cur.n * (1.0 / nLen);
  const DVec3 sRaw = cur.dpdu - n * dot(n, cur.dpdu);
  const double sLen = norm(sRaw);
  const DVec3 s = sRaw * (1.0 / sLen), t = cross(n, s);
  const DVec3 toPrev = prev.p - cur.p, toNext = next.p - cur.p;
  const double aLen = norm(toPrev), bLen = norm(toNext);
  const DVec3 wi = toPrev * (1.0 / aLen), wo = toNext * (1.0 / bLen);
  // The sides, and so the indices of refraction, do not change under a small move.
  const double etaIn = iorOnSide(cur, toPrev), etaOut = iorOnSide(cur, toNext);
  const DVec3 hRaw = wi * etaIn + wo * etaOut;
  const double hLen = norm(hRaw);
  const DVec3 h = hRaw * (1.0 / hLen);
  value[0] = dot(h, s);
  value[1] = dot(h, t);
  if (!a) return;
  for (int axis = 0; axis < 2; ++axis) {
    // x_{i-1} moves: wi turns.
    const DVec3 dhPrev = normalizedAlong(h, hLen, normalizedAlong(wi, aLen, axis ? prev.dpdv : prev.dpdu) * etaIn);
    a[axis] = dot(dhPrev, s), a[2 + axis] = dot(dhPrev, t);
    // x_{i+1} moves: wo turns.
    const DVec3 dhNext = normalizedAlong(h, hLen, normalizedAlong(wo, bLen, axis ? next.dpdv : next.dpdu) * etaOut);
    c[axis] = dot(dhNext, s), c[2 + axis] = dot(dhNext, t);
    // x_i moves: both directions turn, and so do the normal and the frame (dpdu is fixed).
    const DVec3 e = (axis ? cur.dpdv : cur.dpdu) * -1.0;
    const DVec3 dh = normalizedAlong(h, hLen, normalizedAlong(wi, aLen, e) * etaIn + normalizedAlong(wo, bLen, e) * etaOut);
    const DVec3 dn = normalizedAlong(n, nLen, axis ? cur.dndv : cur.dndu);
    const DVec3 ds = normalizedAlong(s, sLen, (dn * dot(n, cur.dpdu) + n * dot(dn, cur.dpdu)) * -1.0);
    const DVec3 dt = cross(dn, s) + cross(n, ds);
    b[axis] = dot(dh, s) + dot(h, ds), b[2 + axis] = dot(dh, t) + dot(h, dt);
  }
}

// 2x2 matrices, row-major.
struct M2 {
  double a = 0, b = 0, c = 0, d = 0;
};
M2 mul(M2 x, M2 y) {
  return {x.a * y.a + x.b * y.c, x.a * y.b + x.b * y.d, x.c * y.a + x.d * y.c, x.c * y.b + x.d * y.d};
}
M2 sub(M2 x, M2 y) { return {x.a - y.a, x.b - y.b, x.c - y.c, x.d - y.d}; }
bool inverse(M2 m, M2& out) {
  const double det = m.a * m.d - m.b * m.c;
  const double scale = std::max({std::abs(m.a), std::abs(m.b), std::abs(m.c), std::abs(m.d)});
  if (!(std::abs(det) > 1e-14 * scale * scale)) return false;
  out = {m.d / det, -m.b / det, -m.c / det, m.a / det};
  return true;
}
void apply(M2 m, const double x[2], double out[2]) {
  const double x0 = x[0], x1 = x[1];
  out[0] = m.a * x0 + m.b * x1;
  out[1] = m.c * x0 + m.d * x1;
}
M2 fromRows(const double r[4]) { return {r[0], r[1], r[2], r[3]}; }

}  // namespace

bool scatterAtManifoldVertex(const ManifoldVertex& v, DVec3 incoming, DVec3& out) {
  const DVec3 wi = incoming * -1.0;
  double cosI = dot(wi, v.n);
  if (v.reflect) {
    out = v.n * (2 * cosI) - wi;
    return true;
  }
  DVec3 n = v.n;
  double ratio = 1.0 / v.eta;  // from the exterior (index 1) into the interior
  if (cosI < 0) {
    ratio = v.eta;
    n = n * -1.0;
    cosI = -cosI;
  }
  const double sin2T = ratio * ratio * (1 - cosI * cosI);
  if (sin2T >= 1) return false;
  out = wi * -ratio + n * (ratio * cosI - std::sqrt(1 - sin2T));
  return true;
}

void manifoldConstraint(const ManifoldChain& chain, int i, double c[2]) {
  constraintAndBlocks(chain, i, c, nullptr, nullptr, nullptr);
}

void manifoldConstraintBlocks(const ManifoldChain& chain, int i, double a[4], double b[4], double c[4]) {
  double value[2];
  constraintAndBlocks(chain, i, value, a, b, c);
}

bool manifoldTangentMoves(const ManifoldChain& chain, int count, const double (*endpointMoves)[2],
                          double* const* moves) {
  const int n = int(chain.size()) - 1;
  const int k = n - 1;  // specular vertices x_1 .. x_{n-1}
  if (k <= 0 || count < 1 || count > 2) return false;
  // Rows i = 1 .. k: A_i d_{i-1} + B_i d_i + C_i d_{i+1} = 0, with d_0 = 0 and d_n given, by
  // block elimination (Thomas): C'_i = D_i^-1 C_i, r'_i = D_i^-1 (r_i - A_i r'_{i-1}),
  // D_i = B_i - A_i C'_{i-1}; then back substitution. One elimination serves every
  // right-hand side.
  std::array<M2, kMaxManifoldVertices> upper;
  std::array<double, 2 * kMaxManifoldVertices> rhs[2] = {};
  for (int i = 1; i <= k; ++i) {
    double a[4], b[4], c[4];
    manifoldConstraintBlocks(chain, i, a, b, c);
    M2 diag = fromRows(b);
    double r[2][2] = {};
    for (int m = 0; m < count; ++m) {
      if (i == k) {  // the endpoint's move, to the right-hand side
        apply(fromRows(c), endpointMoves[m], r[m]);
        r[m][0] = -r[m][0], r[m][1] = -r[m][1];
      }
      if (i > 1) {
        double carried[2];
        apply(fromRows(a), &rhs[m][size_t(2 * (i - 2))], carried);
        r[m][0] -= carried[0], r[m][1] -= carried[1];
      }
    }
    if (i > 1) diag = sub(diag, mul(fromRows(a), upper[size_t(i - 2)]));
    M2 inv;
    if (!inverse(diag, inv)) return false;
    upper[size_t(i - 1)] = mul(inv, fromRows(c));
    for (int m = 0; m < count; ++m) apply(inv, r[m], &rhs[m][size_t(2 * (i - 1))]);
  }
  for (int m = 0; m < count; ++m) {
    for (int i = k; i >= 1; --i) {
      double* d = &moves[m][size_t(2 * (i - 1))];
      d[0] = rhs[m][size_t(2 * (i - 1))], d[1] = rhs[m][size_t(2 * (i - 1) + 1)];
      if (i < k) {
        double next[2];
        apply(upper[size_t(i - 1)], &moves[m][size_t(2 * i)], next);
        d[0] -= next[0], d[1] -= next[1];
      }
    }
  }
  return true;
}

bool manifoldTangentMoves(const ManifoldChain& chain, const double endpointMove[2], double* moves) {
  const double one[1][2] = {{endpointMove[0], endpointMove[1]}};
  return manifoldTangentMoves(chain, 1, one, &moves);
}

bool retraceChain(const ManifoldTracer& tracer, const ManifoldChain& chain, DVec3 direction,
                  ManifoldChain& out) {
  out.assign(1, chain.front());
  DVec3 origin = chain.front().p, dir = unit(direction);
  for (size_t j = 1; j < chain.size(); ++j) {
    ManifoldVertex hit;
    if (!tracer.intersect(origin, dir, hit) || hit.surface != chain[j].surface) return false;
    hit.reflect = chain[j].reflect;  // the chain's interaction, of the surface's possible ones
    out.push_back(hit);
    if (j + 1 == chain.size()) break;
    DVec3 next;
    if (!scatterAtManifoldVertex(hit, dir, next)) return false;
    origin = hit.p;
    dir = unit(next);
  }
  return true;
}

void startManifoldWalk(ManifoldWalk& w) {
  w.step = 1;
  w.result = ManifoldWalkResult{};
  w.result.distance = norm(w.chain.back().p - w.target);
  w.ended = w.chain.size() < 3 || w.result.distance <= w.tolerance;  // < 3: no specular vertex to walk
  w.result.converged = w.result.distance <= w.tolerance;
}

bool manifoldWalkAim(ManifoldWalk& w, DVec3& direction) {
  if (w.ended) return false;
  ManifoldChain& chain = w.chain;
  const size_t n = chain.size() - 1;
  if (w.result.iterations >= w.maxIterations) {
    w.ended = true;
    return false;
  }
  ++w.result.iterations;
  // The endpoint's move in its (u, v): least squares of the offset onto its tangents.
  const ManifoldVertex& end = chain[n];
  const DVec3 offset = w.target - end.p;
  const double guu = dot(end.dpdu, end.dpdu), guv = dot(end.dpdu, end.dpdv), gvv = dot(end.dpdv, end.dpdv);
  const double det = guu * gvv - guv * guv;
  double moves[2 * kMaxManifoldVertices];
  const double ou = dot(offset, end.dpdu), ov = dot(offset, end.dpdv);
  const double move[2] = {w.step * (gvv * ou - guv * ov) / det, w.step * (guu * ov - guv * ou) / det};
  if (!(std::abs(det) > 0) || !manifoldTangentMoves(chain, move, moves)) {
    w.ended = true;
    return false;
  }
  const DVec3 aim = chain[1].p + chain[1].dpdu * moves[0] + chain[1].dpdv * moves[1];
  direction = aim - chain[0].p;
  return true;
}

void manifoldWalkTake(ManifoldWalk& w, bool retraced, ManifoldChain& trial) {
  const size_t n = w.chain.size() - 1;
  double distance = 0;
  if (retraced && trial.size() == w.chain.size() && (distance = norm(trial[n].p - w.target)) < w.result.distance) {
    w.chain.swap(trial);
    w.result.distance = distance;
    w.step = std::min(1.0, 2 * w.step);
  } else {
    w.step *= 0.5;  // too far for the first-order prediction: a shorter step
    if (w.step < 1e-6) w.ended = true;
  }
  w.result.converged = w.result.distance <= w.tolerance;
  if (w.result.converged) w.ended = true;
}

ManifoldWalkResult manifoldWalk(const ManifoldTracer& tracer, ManifoldChain& chain, DVec3 target,
                                double tolerance, int maxIterations) {
  ManifoldWalk w;
  w.chain.swap(chain);
  w.target = target;
  w.tolerance = tolerance;
  w.maxIterations = maxIterations;
  startManifoldWalk(w);
  DVec3 direction;
  ManifoldChain trial;
  while (manifoldWalkAim(w, direction)) manifoldWalkTake(w, retraceChain(tracer, w.chain, direction, trial), trial);
  chain.swap(w.chain);
  return w.result;
}

}  // namespace erpt
