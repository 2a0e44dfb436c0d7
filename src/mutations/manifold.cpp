// The manifold perturbation (Jakob and Marschner 2012, section 5, on ERPT's chains;
// docs/manifold.md): the film position moves uniformly in a disk of the perturbation's radius,
// the eye ray follows the current path's specular lobes to its first non-specular vertex b, and
// the specular chain from b to the next fixed vertex c (a light, or a non-specular vertex) is
// walked on its manifold with c fixed until it ends at the new b (the manifold stage,
// stages/chain_manifold.cpp, which also walks back to check that z can propose y).
//
// Measure: the film position, with c and everything after it fixed. In it
//   f(x) = h(film) prod_{j<b} S_j  f_b(x_b) |cos_b|  prod_{b<j<c} S_j  |d omega_b / dA_c|  E_c
// (S: the specular lobes' values, E_c: the light's emission, or c's BSDF and the fixed tail).
// |d omega_b / dA_c| = G(x_c <-> x_b) / |cos_g at b| is the chain's generalised geometry term,
// which needs the surfaces' curvature and so the tracer's hits: the stage measures it for y and
// z and hands their ratio over in proposals.measureRatio; `contribution` here is the rest,
// which the vertices alone give.
//
// T: the film position is uniform in the disk both ways, and the walks are deterministic, so
// T(z -> y) / T(y -> z) is 1 when y's film position lies in z's disk and the walk back from z
// reaches y (checked by the stage), else 0.
#include <algorithm>

#include "core/rng.h"

#include "eye_walk_start.h"
#include "mutations/mutation.h"
#include "path_factors.h"

namespace erpt {

int manifoldChainEnd(const uint8_t* kinds, int n, int* first) {
  if (n < 4 || n > kMaxChainVertices) return -1;
  int b = 1;
  while (b < n && kinds[b] == kSpecularVertex) ++b;
  if (b + 2 >= n || kinds[b] != kNonSpecularVertex || kinds[b + 1] != kSpecularVertex) return -1;
  int c = b + 1;
  while (c < n && kinds[c] == kSpecularVertex) ++c;
  if (c >= n) return -1;
  // A fixed end with a position: a light, or a non-specular vertex with something after it
  // (a folded path's tail vertex holds the rest).
  if (kinds[c] != kLightVertex && !(kinds[c] == kNonSpecularVertex && c + 1 < n)) return -1;
  if (first) *first = b;
  return c;
}

Color manifoldContribution(const MeasureContext& c, const PathVertex* path, int n, float filmX, float filmY,
                           FixedTail* tail) {
  uint8_t kinds[kMaxChainVertices];
  if (n > kMaxChainVertices) return Color(0.0f);
  for (int j = 0; j < n; ++j) kinds[j] = path[j].kind;
  int b = 0;
  const int end = manifoldChainEnd(kinds, n, &b);
  if (end < 0) return Color(0.0f);
  Color f(c.film.density(filmX, filmY));
  if (isBlack(f)) return f;
  for (int j = 1; j < end; ++j) {
    const Vec3 toPrev = directionBetween(path[j], path[j - 1]), toNext = directionBetween(path[j], path[j + 1]);
    f *= j == b ? factors::evalAt(c, path[j], toPrev, toNext) : factors::specularAt(c, path[j], toPrev, toNext, false);
  }
  const PathVertex& e = path[end];
  const Vec3 toChain = directionBetween(e, path[end - 1]);
  if (e.kind == kLightVertex) return f * factors::emittedAlong(c, e, toChain);
  f *= factors::evalAt(c, e, toChain, directionBetween(e, path[end + 1]));
  return f * factors::tailFrom(c, path, n, end + 1, tail);
}

namespace {

bool appliesToSpecularChains(const uint8_t* kinds, int n) {
  return manifoldChainEnd(kinds, n) > 0;
}

int manifoldTailStart(const uint8_t* kinds, int n) {
  const int end = manifoldChainEnd(kinds, n);
  return end < 0 ? n : std::min(n, end + 1);
}

// The eye walk regenerates up to b; connecting to c across the chain is the manifold stage's
// (stageChainTrace hands it the proposals whose target lies beyond the next vertex).
bool manifoldPlan(uint64_t signature, int n, int& regenLast, int& connectTo) {
  uint8_t kinds[kMaxChainVertices];
  unpackSignature(signature, n, kinds);
  connectTo = manifoldChainEnd(kinds, n, &regenLast);
  return connectTo > 0;
}

void startManifoldRange(const StepConfig& ctx, const ChainQueue& chains, const VertexQueue& chainVertices,
                        ProposalQueue& proposals, RayQueue& rays, IndexRange range) {
  startEyeWalks<diskOffset, manifoldPlan>(MutationKind::Manifold, ctx, chains, chainVertices, proposals, rays, range);
}

float manifoldRatio(const MeasureContext&, const CurrentPath& y, const CurrentPath& z, float size) {
  return withinDisk(y, z, size) ? 1.0f : 0.0f;  // 1 / (pi size^2) both ways; the walk back: the stage's
}

}  // namespace

extern const Mutation kManifoldMutation{MutationKind::Manifold, MutationKind::Manifold, appliesToSpecularChains,
                                        startManifoldRange, manifoldTailStart, manifoldContribution, manifoldRatio,
                                        perturbationAcceptance, moveToPerturbation};

bool choosesManifold(const StepConfig& ctx, const ChainQueue& chains, size_t i, const uint8_t* kinds, int n) {
  const float p = ctx.settings.manifold;
  return p > 0 && manifoldChainEnd(kinds, n) > 0 &&
         uniformDouble(chains.key[i], stepDim(chains.step[i], kDimManifold)) < double(p);
}

}  // namespace erpt
