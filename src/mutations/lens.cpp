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
#include "eye_walk_start.h"

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

// The lens walk's plan from the packed signature (lens starts never unpack the path): the eye
// ray's walk regenerates up to the connection target, or to the light when it is reached by
// tracing.
bool lensPlan(uint64_t signature, int n, int& regenLast, int& connectTo) {
  connectTo = connectionTarget([signature](int j) { return kindAt(signature, j); }, n);
  regenLast = connectTo > 0 ? connectTo - 1 : n - 1;
  return true;
}

void startSquareRange(const StepConfig& ctx, const ChainQueue& chains, const VertexQueue& chainVertices,
                      ProposalQueue& proposals, RayQueue& rays, IndexRange range) {
  startEyeWalks<squareOffset, lensPlan>(MutationKind::Lens, ctx, chains, chainVertices, proposals, rays, range);
}

void startDiskRange(const StepConfig& ctx, const ChainQueue& chains, const VertexQueue& chainVertices,
                    ProposalQueue& proposals, RayQueue& rays, IndexRange range) {
  startEyeWalks<diskOffset, lensPlan>(MutationKind::LensDisk, ctx, chains, chainVertices, proposals, rays, range);
}

float diskRatio(const MeasureContext&, const CurrentPath& y, const CurrentPath& z, float size) {
  return withinDisk(y, z, size) ? 1.0f : 0.0f;  // 1 / (pi size^2) both ways
}

float squareRatio(const MeasureContext&, const CurrentPath& y, const CurrentPath& z, float size) {
  const bool inside = std::abs(y.filmX - z.filmX) <= size + kFilmSlack && std::abs(y.filmY - z.filmY) <= size + kFilmSlack;
  return inside ? 1.0f : 0.0f;  // 1 / (2 size)^2 both ways
}


}  // namespace

extern const Mutation kLensSquareMutation{MutationKind::Lens, MutationKind::Lens, appliesToAnyChainPath, startSquareRange,
                                          lensTailStart, lensContribution, squareRatio, perturbationAcceptance, moveToPerturbation};
extern const Mutation kLensDiskMutation{MutationKind::LensDisk, MutationKind::Lens, appliesToAnyChainPath, startDiskRange,
                                        lensTailStart, lensContribution, diskRatio, perturbationAcceptance, moveToPerturbation};

}  // namespace erpt
