// Manifold exploration's walk along a specular chain (Jakob and Marschner 2012, sections 4
// and 5; the derivation is in docs/manifold.md).
//
// A chain x_0 .. x_n has specular vertices x_1 .. x_{n-1} between two endpoints. Each specular
// vertex constrains its neighbours through the generalised half vector
//     h_i = eta(w_in) w_in + eta(w_out) w_out,   w = unit directions from x_i to x_{i-1}, x_{i+1},
// eta(w) the index of refraction on w's side of the surface: the law of reflection and Snell's
// law both say that h_i is along the normal, i.e. that its tangential part c_i = (h_i . s_i,
// h_i . t_i) / |h_i| is zero. The paths that satisfy every c_i = 0 form a manifold; moving the
// endpoint x_n along its surface moves the specular vertices along it.
//
// The walk keeps x_0 fixed and brings x_n to a target: from the chain's constraint Jacobian
// (block tridiagonal, 2x2 blocks per vertex pair) it predicts the specular vertices' tangent
// moves for the endpoint's move, aims from x_0 at the predicted x_1 and retraces the chain by
// the laws of reflection and refraction (so every state it reaches is on the manifold), and
// takes the step if the endpoint came closer to the target; otherwise it halves the step.
//
// Everything here is per chain and in double precision; the retracing is the caller's
// (ManifoldTracer): one ray per vertex of the chain.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>

namespace erpt {

struct DVec3 {
  double x = 0, y = 0, z = 0;
};
inline DVec3 operator+(DVec3 a, DVec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline DVec3 operator-(DVec3 a, DVec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline DVec3 operator*(DVec3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
inline DVec3 operator*(double s, DVec3 a) { return a * s; }
inline double dot(DVec3 a, DVec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline DVec3 cross(DVec3 a, DVec3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }

// A vertex of a chain as the walk sees it: where it is, how its surface and normal turn there,
// and what it does to light.
struct ManifoldVertex {
  DVec3 p;           // position
  DVec3 dpdu, dpdv;  // surface tangents (any two independent ones)
  DVec3 n;           // unit shading normal
  DVec3 dndu, dndv;  // derivatives of the shading normal along dpdu and dpdv (its curvature)
  // Specular vertices: the index of refraction on the side the normal points away from (the
  // exterior's is 1); and whether the chain reflects or refracts here.
  double eta = 1;
  bool reflect = true;
  uint32_t surface = 0;  // which surface (a shape, Scene::shapes): a retraced chain must meet the same ones
  // Where the scene's tracer found it (kernels/manifold_retrace.h): its primitive and hit
  // coordinates, from which the renderer's own surface point is made; ~0u for analytic tests.
  uint32_t primitive = ~0u;
  float hitU = 0, hitV = 0;
};

// Most vertices a chain may have (its two ends included).
constexpr int kMaxManifoldVertices = 24;

// A chain's vertices, held in place: a stage's thousands of walks allocate nothing. (The
// part of std::vector's interface the walks use.)
class ManifoldChain {
 public:
  ManifoldChain() = default;
  explicit ManifoldChain(size_t n) { resize(n); }
  size_t size() const { return n_; }
  bool empty() const { return n_ == 0; }
  ManifoldVertex& operator[](size_t i) { return v_[i]; }
  const ManifoldVertex& operator[](size_t i) const { return v_[i]; }
  ManifoldVertex& front() { return v_[0]; }
  const ManifoldVertex& front() const { return v_[0]; }
  ManifoldVertex& back() { return v_[n_ - 1]; }
  const ManifoldVertex& back() const { return v_[n_ - 1]; }
  // False (and the chain unchanged) when it is full.
  bool push_back(const ManifoldVertex& v) {
    if (n_ == size_t(kMaxManifoldVertices)) return false;
    v_[n_++] = v;
    return true;
  }
  void resize(size_t n) { n_ = n < size_t(kMaxManifoldVertices) ? n : size_t(kMaxManifoldVertices); }
  void assign(size_t n, const ManifoldVertex& v) {
    resize(n);
    for (size_t i = 0; i < n_; ++i) v_[i] = v;
  }
  void clear() { n_ = 0; }
  // Copies only the vertices in use.
  ManifoldChain(const ManifoldChain& o) : n_(o.n_) {
    for (size_t i = 0; i < n_; ++i) v_[i] = o.v_[i];
  }
  ManifoldChain& operator=(const ManifoldChain& o) {
    n_ = o.n_;
    for (size_t i = 0; i < n_; ++i) v_[i] = o.v_[i];
    return *this;
  }
  void swap(ManifoldChain& o) {
    const size_t m = n_ > o.n_ ? n_ : o.n_;
    for (size_t i = 0; i < m; ++i) std::swap(v_[i], o.v_[i]);
    std::swap(n_, o.n_);
  }

 private:
  std::array<ManifoldVertex, kMaxManifoldVertices> v_;
  size_t n_ = 0;
};

// The tangential part of the generalised half vector at the chain's specular vertex i
// (1 <= i < n): zero on the manifold.
void manifoldConstraint(const ManifoldChain& chain, int i, double c[2]);

// The 2x2 blocks of constraint i's derivatives with respect to the (u, v) moves
// x + u dpdu + v dpdv of its vertex's neighbours and itself: d c_i / d x_{i-1} (a), d x_i (b),
// d x_{i+1} (c), each row-major [dc0/du, dc0/dv, dc1/du, dc1/dv]. Exact first derivatives
// (the chain rule through the formula's normalisations; tested against central differences).
void manifoldConstraintBlocks(const ManifoldChain& chain, int i, double a[4], double b[4], double c[4]);

// The moves (du, dv) of the specular vertices x_1 .. x_{n-1} that keep every constraint at
// first order when the endpoint x_n moves by (du_n, dv_n) along its surface and x_0 stays:
// the block tridiagonal solve of the paper. False when the system is singular there.
// `moves` holds 2 (n - 1) numbers: (du, dv) of x_1, then of x_2, ...
bool manifoldTangentMoves(const ManifoldChain& chain, const double endpointMove[2], double* moves);
// The same for one or two endpoint moves at once (one elimination): moves[m] for endpointMoves[m].
bool manifoldTangentMoves(const ManifoldChain& chain, int count, const double (*endpointMoves)[2],
                          double* const* moves);

// Retraces a chain: from `origin`, a ray along `direction`; at every specular vertex the
// chain's interaction (reflection, or refraction with its eta) gives the next ray. Fills the
// vertices hit after the origin (chain order) and returns false if a ray missed, hit another
// surface than `surfaces` names in order, or found total internal reflection where the chain
// refracts. The caller traces the rays (a ray caster, or the tracer's streams).
// The direction in which the chain leaves its specular vertex v, hit by a ray travelling
// along `incoming` (v.reflect: reflection, else refraction with v.eta); false at total
// internal reflection where the chain refracts.
bool scatterAtManifoldVertex(const ManifoldVertex& v, DVec3 incoming, DVec3& out);

class ManifoldTracer {
 public:
  virtual ~ManifoldTracer() = default;
  // The first surface point along the ray, or false.
  virtual bool intersect(DVec3 origin, DVec3 direction, ManifoldVertex& hit) const = 0;
};
bool retraceChain(const ManifoldTracer& tracer, const ManifoldChain& chain, DVec3 direction,
                  ManifoldChain& out);

// The generalised geometry term of the chain between its endpoints (manifold_geometry.cpp):
// |cos theta_0| |d omega_0 / dA(x_n)|, the projected solid angle at x_0 per area at x_n
// when x_n moves on its surface and the specular vertices follow it on the manifold. For a
// chain without specular vertices it is the usual cos theta_0 cos theta_n / r^2. 0 where the
// tangent system is singular.
double generalizedGeometry(const ManifoldChain& chain);

struct ManifoldWalkResult {
  bool converged = false;
  int iterations = 0;  // Newton steps taken (accepted or halved)
  double distance = 0; // |x_n - target| at the end
};
// One walk as a state machine, so that many walks can share the tracer's ray streams
// (kernels/manifold_retrace.h): manifoldWalkAim gives the direction from chain[0] of the next
// retrace, or false once the walk has ended; manifoldWalkTake hands it the retraced chain
// (`retraced` false: the retrace failed). The chain, on the manifold, is brought until its
// endpoint is within `tolerance` of `target`, a point on the endpoint's surface near it, in at
// most `maxIterations` steps; on success it holds the new path.
struct ManifoldWalk {
  ManifoldChain chain;
  DVec3 target;
  double tolerance = 0;
  int maxIterations = 50;
  double step = 1;  // the share of the first-order move tried next (halved after a failed try)
  ManifoldWalkResult result;
  bool ended = false;
};
void startManifoldWalk(ManifoldWalk& w);
bool manifoldWalkAim(ManifoldWalk& w, DVec3& direction);
void manifoldWalkTake(ManifoldWalk& w, bool retraced, ManifoldChain& trial);

// The same walk, retraced one ray at a time by `tracer`.
ManifoldWalkResult manifoldWalk(const ManifoldTracer& tracer, ManifoldChain& chain, DVec3 target,
                                double tolerance, int maxIterations = 50);

}  // namespace erpt
