// MLT's large step (docs/mlt.md): an independent proposal, a fresh path-tracer sample through a
// uniformly chosen pixel, which keeps the Metropolis chains ergodic. The path tracer makes
// one candidate path per length n and technique (its BSDF sample hitting the light: "hit"; its
// next-event connection: "nee"); the large step first draws a length n with probability P(n)
// and a technique with P(nee | n), and proposes that candidate (none: the proposal is
// rejected). Its density is therefore
//   q(z) = P(n) [P(hit | n) p_hit(z) + P(nee | n) p_nee(z)],
// with p_hit and p_nee the path tracer's densities of making z by each technique (camera
// sample, BSDF sampling, Russian roulette, light sampling), and since q does not depend on the
// current path y, the acceptance is min(1, W(z) / W(y)) with W = lum(f) / q. Both f and q carry
// the film density H(x) / pixels of the camera sample, which cancels in W (erpt_path.h's
// MeasureContext: f is the path tracer's measurement contribution times H).
#pragma once

#include "kernels/erpt_path.h"

namespace erpt {

// What the large step draws from and what its density depends on.
struct LargeStepModel {
  float probability = 0.3f;  // the chance that a chain step is a large step
  // The chains' path lengths (vertices, eye and light included).
  int minVertices = 2, maxVertices = kMaxChainVertices;
  float lengthProbability[kMaxChainVertices + 1] = {};  // P(n); sums to 1 over [min, max]
  float neeShare[kMaxChainVertices + 1] = {};           // P(nee | n)
  int rrDepth = 5;  // the path tracer's Russian roulette depth (StageContext::rrDepth)
  // P(nee | n); an emitter seen directly (n = 2) has only the hit.
  float neeProbability(int n) const { return n >= 3 ? neeShare[n] : 0.0f; }
  // From the bootstrap's energy of the chains' paths by vertex count (`energyByLength`) and the
  // part of it next-event estimation found (`neeEnergyByLength`; null: none known):
  //   P(n) = 0.7 x its share of the energy + 0.3 uniform over [minVertices, maxVertices],
  //   P(nee | n) = next-event estimation's share of that energy, clamped to [0.1, 0.9],
  // so that every length and technique the chains hold keeps a positive probability, and the
  // large steps go where the energy is (without energy: uniform lengths, a fair coin). With
  // 0.1 uniform, chains of large steps alone stuck on rarely proposed long paths (heavy-tailed
  // renders); with 0.5 and a fair coin, 87% of the large steps on the Cornell box found no
  // candidate (now 70%).
  void setLengths(const double* energyByLength, const double* neeEnergyByLength = nullptr);
};

// The parts of a path's large-step density: `value` is f(y) over the density of everything but
// the last vertex (RGB: the path tracer's throughput to the last surface vertex times that
// vertex's BSDF, the light's emission and the last segment's area factor), `pHit` and `pNee`
// the densities of the last vertex by the two techniques (area measure; solid angle for the
// environment; the pick probability for a point light). value / pHit and value / pNee are the
// path tracer's unweighted estimates of the path by each technique.
struct LargeStepTerms {
  Color value{0.0f};
  float pHit = 0, pNee = 0;
};
// False when the path tracer cannot make the path (no light at its end, a zero BSDF value or
// density on the way); then W = 0.
bool largeStepTerms(const MeasureContext& c, int rrDepth, const PathVertex* path, int n, LargeStepTerms& out);
// W(y) = lum(f(y)) / q(y), up to the constant factor shared by all paths; 0 when q or f is 0.
float largeStepWeight(const MeasureContext& c, const LargeStepModel& m, const PathVertex* path, int n);

}  // namespace erpt
