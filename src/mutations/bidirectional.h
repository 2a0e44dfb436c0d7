// Veach's bidirectional mutation (Veach 1997, thesis section 11.4.2; docs/bidirectional-mutation.md):
// delete the vertices of the current path y strictly between vertex l and vertex m, and
// regenerate `added` new vertices in their place, `eyeSide` of them by a walk from vertex l
// (BSDF sampling; from the eye: a film position uniform over the image) and the rest by a walk
// from vertex m towards the eye (adjoint BSDF sampling; from a light vertex its emission
// sampling), then join the two walks' ends by a connection. With m = n the light vertex is
// deleted too and the light-side walk starts at a new light point (emission sampling). The
// path's length changes with added != deleted.
//
// What it leaves to the other mutations: the eye vertex is always kept (l >= 0), the
// connection never joins at the eye, and the light-side walk always makes a deleted light's
// replacement, so paths with two vertices (an emitter seen directly) are never proposed (their
// proposals are irreversible); the environment is never deleted nor walked from.
//
// The acceptance (Metropolis-Hastings) is min(1, f(z) T(z -> y) / (f(y) T(y -> z))) with f in
// this unit's measure (film position for vertex 1, area for the others: solid angle for the
// environment; a point light's position is a Dirac) and
//   T(y -> z) = P_del(l, m | y) P_add(added | y, l, m) sum_t P(t) p_t(z),
// the sum running over every split t of the new vertices into eye-side and light-side walks
// that could have made z: the proposal density does not depend on which split did.
#pragma once

#include "kernels/erpt_path.h"
#include "mutations/step_config.h"

namespace erpt {

struct BidirectionalPlan {
  int l = 0;        // last kept vertex on the eye side
  int m = 0;        // first kept vertex on the light side; the path's n: the light is replaced
  int added = 0;    // new vertices
  int eyeSide = 0;  // of them made by the eye-side walk (vertices l + 1 .. l + eyeSide)
  int deleted() const { return m - l - 1; }
};

// Whether the light vertex of `path` may be deleted: an area or point light's (not the
// environment, which has no position to sample, nor a folded tail).
bool lightDeletable(const MeasureContext& c, const PathVertex* path, int n);
// Whether the mutation applies to a path: 2 <= n <= kMaxChainVertices, no folded tail.
bool bidirectionalApplies(const uint8_t* kinds, int n);

// The plan's probabilities, each a function of the path it is drawn from (n vertices, light
// deletable or not) and the chain's length limit:
//   P(l, m): kd = m - l with probability proportional to 1/4, 1/2, 2^-kd (kd >= 3) over the
//   kd the path allows, then l uniform;
//   P(added | l, m): proportional to 2^-|added - deleted| over the counts that keep the
//   path's length in `lengths` and leave room for the walks' required vertices;
//   P(eyeSide | added): uniform over the splits that keep the eye and replace a deleted light.
double deletionProbability(int n, bool lightDeletable, int l, int m);
double additionProbability(int n, VertexRange lengths, int l, int m, int added);
int eyeSideMin(int l);
int eyeSideMax(int n, int m, int added);
// Draws a plan from dimensions [dim, dim + 4) of random stream `key`; false when the path
// allows none.
bool drawBidirectionalPlan(int n, bool lightDeletable, VertexRange lengths, uint64_t key, uint32_t dim,
                           BidirectionalPlan& out);
// The vertex count of the proposed path.
inline int proposedVertices(int n, const BidirectionalPlan& p) { return n - p.deleted() + p.added; }

// f in the mutation's measure (the film density H at the path's film position included); 0
// for a path it does not hold (a folded tail, no light at the end).
Color bidirectionalContribution(const MeasureContext& c, const PathVertex* path, int n, float filmX, float filmY);

// sum_t P(t) p_t over the splits of the new vertices [l + 1, l + added] of `path` (n vertices;
// lightReplaced: the last of them is the light vertex), in the measure of
// bidirectionalContribution. A split needs the two vertices its connection joins to be
// connectable (not specular, never the eye).
double regeneratedDensity(const MeasureContext& c, const PathVertex* path, int n, int l, int added, bool lightReplaced);

// T(y -> z) for z proposed from y by deleting (l, m) and adding `added` vertices.
double bidirectionalTransition(const MeasureContext& c, VertexRange lengths, const PathVertex* y, int ny, int l, int m,
                               const PathVertex* z, int nz, int added);

// f(z) T(z -> y) / (f(y) T(y -> z)) on luminance (film positions: the paths' own); 0 when the
// reverse is impossible or f(y) is 0.
double bidirectionalRatio(const MeasureContext& c, VertexRange lengths, const PathVertex* y, int ny, float yFilmX,
                          float yFilmY, const PathVertex* z, int nz, float zFilmX, float zFilmY,
                          const BidirectionalPlan& plan);

}  // namespace erpt
