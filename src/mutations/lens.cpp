// The lens perturbation (ERPT paper section 4.3, after Veach and Guibas 1997): the film
// position moves, uniformly in a square of half-side `size` pixels (ERPT) or in a disk of
// radius `size` (PMC-ER); the eye ray through it follows the current path's specular lobes,
// its direction is perturbed at non-specular vertices followed by specular ones, and the last
// regenerated vertex connects to the next fixed vertex (or the walk reaches the light by
// tracing). Both distributions are symmetric: T(z -> y) / T(y -> z) is 1 when y lies in z's
// square (disk), which it does whenever z lies in y's, and 0 otherwise.
#include <cmath>

#include "models/camera.h"
#include "mutations/mutation.h"
#include "path_factors.h"
#include "core/rng.h"
#include "tracer/tracer.h"

namespace erpt {

namespace {

// The first non-specular vertex j not followed by a specular one connects to j + 1.
template <class KindOf>
int connectionTarget(KindOf kindOf, int n) {
  for (int j = 1; j < n; ++j) {
    const uint8_t k = kindOf(j);
    if (k == kLightVertex || k == kEnvironmentVertex) return -1;  // reached by tracing
    if (k == kTailVertex) return -1;  // a folded path's tail is never regenerated
    if (k == kSpecularVertex || (j + 1 < n && kindOf(j + 1) == kSpecularVertex)) continue;
    return j + 1;
  }
  return -1;
}

}  // namespace

int lensConnectionTarget(const uint8_t* kinds, int n) {
  return connectionTarget([kinds](int j) { return kinds[j]; }, n);
}

Color lensContribution(const MeasureContext& c, const PathVertex* path, int n, float filmX, float filmY,
                       FixedTail* tail) {
  Color f(c.film.density(filmX, filmY));
  if (isBlack(f)) return f;
  for (int j = 1; j < n; ++j) {
    const PathVertex& v = path[j];
    const Vec3 toPrev = directionBetween(v, path[j - 1]);
    // Reached by tracing: a light or the environment ends the walk (solid-angle measure).
    if (v.kind == kLightVertex || v.kind == kEnvironmentVertex) return f * factors::emittedAlong(c, v, toPrev);
    if (j + 1 >= n || v.kind == kTailVertex) return Color(0.0f);
    const Vec3 toNext = directionBetween(v, path[j + 1]);
    if (v.kind == kSpecularVertex) {
      f *= factors::specularAt(c, v, toPrev, toNext, false);
      continue;
    }
    f *= factors::evalAt(c, v, toPrev, toNext);
    if (path[j + 1].kind == kSpecularVertex) continue;  // perturbed direction: solid angle
    // Connection to the fixed vertex t = j + 1 (area measure), which keeps its outgoing
    // direction but sees a new incoming one; then the rest of the path.
    const PathVertex& t = path[j + 1];
    f *= factors::areaFactor(c, v, t);
    if (t.kind == kLightVertex || t.kind == kEnvironmentVertex) return f * factors::emittedAlong(c, t, -toNext);
    if (j + 2 >= n || t.kind == kTailVertex) return Color(0.0f);
    f *= factors::evalAt(c, t, -toNext, directionBetween(t, path[j + 2]));
    return f * factors::tailFrom(c, path, n, j + 2, tail);
  }
  return Color(0.0f);
}


namespace {

// Film positions a little outside the square or disk by rounding still count as inside.
constexpr float kFilmSlack = 1e-3f;

bool appliesToAnyChainPath(const uint8_t* kinds, int n) {
  if (n < 2 || n > kMaxChainVertices) return false;
  if (kinds[n - 1] != kTailVertex) return true;
  // A folded path: the connection must come before the tail vertex, whose factor holds the
  // direction from the vertex before it.
  const int target = lensConnectionTarget(kinds, n);
  return target > 0 && target < n - 1;
}

int lensTailStart(const uint8_t* kinds, int n) {
  // The connection target's incoming direction changes; the vertices after it do not.
  const int target = lensConnectionTarget(kinds, n);
  return target < 0 ? n : std::min(n, target + 1);
}

// Film positions of the two shapes: uniform in the square of half-side `size`, or in the
// disk of radius `size` (radius size * sqrt(u1), angle 2 pi u2).
void squareOffset(float size, float u1, float u2, float& dx, float& dy) {
  dx = (2 * u1 - 1) * size;
  dy = (2 * u2 - 1) * size;
}

void diskOffset(float size, float u1, float u2, float& dx, float& dy) {
  const float r = size * std::sqrt(u1), phi = 2 * kPi * u2;
  dx = r * std::cos(phi);
  dy = r * std::sin(phi);
}

// The eye rays of a batch of lens starts. A scalar camera ray is a chain of dependent
// divisions and square roots; the camera's vector kernel makes a batch of them at once.
class EyeRayBatch {
 public:
  EyeRayBatch(const Camera& camera, const VertexQueue& chainVertices, RayQueue& rays)
      : camera_(camera), chainVertices_(chainVertices), rays_(rays) {}

  void add(size_t slot, float filmX, float filmY) {
    slot_[count_] = slot;
    filmX_[count_] = filmX;
    filmY_[count_] = filmY;
    if (++count_ == kSize) flush();
  }

  void flush() {
    if (count_ == 0) return;
    float dx[kSize], dy[kSize], dz[kSize], tnear[kSize], tfar[kSize];
    camera_.generateRays(filmX_, filmY_, count_, dx, dy, dz, tnear, tfar);
    for (size_t b = 0; b < count_; ++b) {
      Camera::Ray r{camera_.position(), Vec3(dx[b], dy[b], dz[b]), tnear[b], tfar[b]};
      // From the chain's lens point (vertex 0), which stays fixed.
      if (camera_.hasLens()) r = camera_.refocus(chainVertices_.pAt(slot_[b] * kMaxChainVertices), r);
      setRay(rays_, slot_[b], r.origin, r.direction, r.tnear, r.tfar);
    }
    count_ = 0;
  }

 private:
  static constexpr size_t kSize = 64;

  const Camera& camera_;
  const VertexQueue& chainVertices_;
  RayQueue& rays_;
  size_t slot_[kSize];
  float filmX_[kSize], filmY_[kSize];
  size_t count_ = 0;
};

// Every lens start of a range: the new film position, the walk's plan from the packed
// signature (lens starts never unpack the path), and the eye ray.
template <auto Offset>
void startLensRange(MutationKind kind, const StepConfig& ctx, const ChainQueue& chains, const VertexQueue& chainVertices,
                    ProposalQueue& proposals, RayQueue& rays, IndexRange range) {
  const MeasureContext& c = ctx.measure;
  EyeRayBatch eyeRays(c.camera, chainVertices, rays);
  for (size_t i = range.begin; i < range.end; ++i) {
    if (proposals.mutation[i] != uint8_t(kind) || proposals.state[i] != kProposalWalking) continue;
    const uint64_t key = chains.key[i];
    const uint32_t step = chains.step[i];
    float dx, dy;
    Offset(proposals.perturbSize[i], uniformFloat(key, stepDim(step, kDimStart1)),
           uniformFloat(key, stepDim(step, kDimStart2)), dx, dy);
    const float fx = chains.filmX[i] + dx, fy = chains.filmY[i] + dy;
    proposals.filmX[i] = fx;
    proposals.filmY[i] = fy;
    if (!(c.film.density(fx, fy) > 0)) {
      rejectProposal(proposals, rays, i, kRejectOffFilm);
      continue;
    }
    const uint64_t signature = chains.signature[i];
    const int connectTo = connectionTarget([signature](int j) { return kindAt(signature, j); }, chains.vertexCount[i]);
    proposals.cursor[i] = 1;
    proposals.walk[i] = +1;
    proposals.regenFirst[i] = 1;
    proposals.regenLast[i] = int8_t(connectTo > 0 ? connectTo - 1 : chains.vertexCount[i] - 1);
    proposals.connectTo[i] = int8_t(connectTo);
    eyeRays.add(i, fx, fy);
  }
  eyeRays.flush();
}

void startSquareRange(const StepConfig& ctx, const ChainQueue& chains, const VertexQueue& chainVertices,
                      ProposalQueue& proposals, RayQueue& rays, IndexRange range) {
  startLensRange<squareOffset>(MutationKind::Lens, ctx, chains, chainVertices, proposals, rays, range);
}

void startDiskRange(const StepConfig& ctx, const ChainQueue& chains, const VertexQueue& chainVertices,
                    ProposalQueue& proposals, RayQueue& rays, IndexRange range) {
  startLensRange<diskOffset>(MutationKind::LensDisk, ctx, chains, chainVertices, proposals, rays, range);
}

float squareRatio(const MeasureContext&, const CurrentPath& y, const CurrentPath& z, float size) {
  const bool inside = std::abs(y.filmX - z.filmX) <= size + kFilmSlack && std::abs(y.filmY - z.filmY) <= size + kFilmSlack;
  return inside ? 1.0f : 0.0f;  // 1 / (2 size)^2 both ways
}

float diskRatio(const MeasureContext&, const CurrentPath& y, const CurrentPath& z, float size) {
  const float dx = y.filmX - z.filmX, dy = y.filmY - z.filmY;
  return std::sqrt(dx * dx + dy * dy) <= size + kFilmSlack ? 1.0f : 0.0f;  // 1 / (pi size^2) both ways
}

}  // namespace

extern const Mutation kLensSquareMutation{MutationKind::Lens, MutationKind::Lens, appliesToAnyChainPath, startSquareRange,
                                          lensTailStart, lensContribution, squareRatio, perturbationAcceptance, moveToPerturbation};
extern const Mutation kLensDiskMutation{MutationKind::LensDisk, MutationKind::Lens, appliesToAnyChainPath, startDiskRange,
                                        lensTailStart, lensContribution, diskRatio, perturbationAcceptance, moveToPerturbation};

}  // namespace erpt
