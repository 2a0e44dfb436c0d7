#include "kernels/manifold_walk.h"

#include <algorithm>
#include <cmath>

namespace erpt {

namespace {

// A value and its derivatives along two directions (forward-mode automatic differentiation):
// the constraint's formula evaluated once on these gives its value and one 2x2 Jacobian block.
struct Dual {
  double v = 0, d0 = 0, d1 = 0;
};
Dual operator+(Dual a, Dual b) { return {a.v + b.v, a.d0 + b.d0, a.d1 + b.d1}; }
Dual operator-(Dual a, Dual b) { return {a.v - b.v, a.d0 - b.d0, a.d1 - b.d1}; }
Dual operator*(Dual a, Dual b) { return {a.v * b.v, a.d0 * b.v + a.v * b.d0, a.d1 * b.v + a.v * b.d1}; }
Dual operator/(Dual a, Dual b) {
  const double inv = 1.0 / b.v;
  return {a.v * inv, (a.d0 - a.v * inv * b.d0) * inv, (a.d1 - a.v * inv * b.d1) * inv};
}
Dual sqrtOf(Dual a) {
  const double s = std::sqrt(a.v);
  const double k = s > 0 ? 0.5 / s : 0.0;
  return {s, a.d0 * k, a.d1 * k};
}
Dual constant(double v) { return {v, 0, 0}; }

struct DualVec {
  Dual x, y, z;
};
DualVec operator+(DualVec a, DualVec b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
DualVec operator-(DualVec a, DualVec b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
DualVec operator*(DualVec a, Dual s) { return {a.x * s, a.y * s, a.z * s}; }
Dual dotOf(DualVec a, DualVec b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
DualVec crossOf(DualVec a, DualVec b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
DualVec normalized(DualVec a) {
  const Dual inv = constant(1.0) / sqrtOf(dotOf(a, a));
  return a * inv;
}
DualVec constantVec(DVec3 a) { return {constant(a.x), constant(a.y), constant(a.z)}; }

// `base + u along + v across`, u and v the two derivative directions when `moved`.
DualVec moved(DVec3 base, DVec3 along, DVec3 across, bool isMoved) {
  DualVec out = constantVec(base);
  if (!isMoved) return out;
  out.x.d0 = along.x, out.y.d0 = along.y, out.z.d0 = along.z;
  out.x.d1 = across.x, out.y.d1 = across.y, out.z.d1 = across.z;
  return out;
}

double norm(DVec3 a) { return std::sqrt(dot(a, a)); }
DVec3 unit(DVec3 a) { return a * (1.0 / norm(a)); }

// The index of refraction on direction w's side of vertex v's surface.
double iorOnSide(const ManifoldVertex& v, DVec3 w) { return dot(w, v.n) >= 0 ? 1.0 : v.eta; }

// Constraint i with vertex `which` (0: x_{i-1}, 1: x_i, 2: x_{i+1}; -1: none) moved along its
// (u, v): its value and the derivatives of that move.
void constraintWith(const ManifoldChain& chain, int i, int which, Dual c[2]) {
  const ManifoldVertex &prev = chain[size_t(i - 1)], &cur = chain[size_t(i)], &next = chain[size_t(i + 1)];
  const DualVec a = moved(prev.p, prev.dpdu, prev.dpdv, which == 0);
  const DualVec b = moved(next.p, next.dpdu, next.dpdv, which == 2);
  const DualVec p = moved(cur.p, cur.dpdu, cur.dpdv, which == 1);
  // The normal turns with the vertex's move (its curvature); the tangent frame follows it.
  const DualVec n = normalized(moved(cur.n, cur.dndu, cur.dndv, which == 1));
  const DualVec du = constantVec(cur.dpdu);
  const DualVec s = normalized(du - n * dotOf(n, du));
  const DualVec t = crossOf(n, s);
  const DualVec wi = normalized(a - p), wo = normalized(b - p);
  // The sides, and so the indices of refraction, do not change under a small move.
  const double etaIn = iorOnSide(cur, prev.p - cur.p), etaOut = iorOnSide(cur, next.p - cur.p);
  const DualVec h = normalized(wi * constant(etaIn) + wo * constant(etaOut));
  c[0] = dotOf(h, s);
  c[1] = dotOf(h, t);
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
  Dual d[2];
  constraintWith(chain, i, -1, d);
  c[0] = d[0].v, c[1] = d[1].v;
}

void manifoldConstraintBlocks(const ManifoldChain& chain, int i, double a[4], double b[4], double c[4]) {
  double* blocks[3] = {a, b, c};
  for (int which = 0; which < 3; ++which) {
    Dual d[2];
    constraintWith(chain, i, which, d);
    double* out = blocks[which];
    out[0] = d[0].d0, out[1] = d[0].d1, out[2] = d[1].d0, out[3] = d[1].d1;
  }
}

bool manifoldTangentMoves(const ManifoldChain& chain, const double endpointMove[2], double* moves) {
  const int n = int(chain.size()) - 1;
  const int k = n - 1;  // specular vertices x_1 .. x_{n-1}
  if (k <= 0) return false;
  // Rows i = 1 .. k: A_i d_{i-1} + B_i d_i + C_i d_{i+1} = 0, with d_0 = 0 and d_n given, by
  // block elimination (Thomas): C'_i = D_i^-1 C_i, r'_i = D_i^-1 (r_i - A_i r'_{i-1}),
  // D_i = B_i - A_i C'_{i-1}; then back substitution.
  std::array<M2, kMaxManifoldVertices> upper;
  std::array<double, 2 * kMaxManifoldVertices> rhs{};
  for (int i = 1; i <= k; ++i) {
    double a[4], b[4], c[4];
    manifoldConstraintBlocks(chain, i, a, b, c);
    M2 diag = fromRows(b);
    double r[2] = {0, 0};
    if (i == k) {  // the endpoint's move, to the right-hand side
      apply(fromRows(c), endpointMove, r);
      r[0] = -r[0], r[1] = -r[1];
    }
    if (i > 1) {
      const M2 lower = fromRows(a);
      diag = sub(diag, mul(lower, upper[size_t(i - 2)]));
      double carried[2];
      apply(lower, &rhs[size_t(2 * (i - 2))], carried);
      r[0] -= carried[0], r[1] -= carried[1];
    }
    M2 inv;
    if (!inverse(diag, inv)) return false;
    upper[size_t(i - 1)] = mul(inv, fromRows(c));
    apply(inv, r, &rhs[size_t(2 * (i - 1))]);
  }
  for (int i = k; i >= 1; --i) {
    double* d = &moves[size_t(2 * (i - 1))];
    d[0] = rhs[size_t(2 * (i - 1))], d[1] = rhs[size_t(2 * (i - 1) + 1)];
    if (i < k) {
      double next[2];
      apply(upper[size_t(i - 1)], &moves[size_t(2 * i)], next);
      d[0] -= next[0], d[1] -= next[1];
    }
  }
  return true;
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
