// Veach's bidirectional mutation: its plan's probabilities, f in its measure, the densities of
// the regenerated vertices, and its unit for the accept stage (bidirectional.h; the walks that
// make the proposals are the stage in src/stages/chain_bidirectional.cpp).
#include "mutations/bidirectional.h"

#include <algorithm>
#include <cmath>

#include "core/rng.h"
#include "mutations/mutation.h"
#include "path_factors.h"

namespace erpt {

bool lightDeletable(const MeasureContext& c, const PathVertex* path, int n) {
  const PathVertex& light = path[n - 1];
  if (light.kind != kLightVertex || light.emitter < 0) return false;
  const EmitterKind k = c.scene.emitters[size_t(light.emitter)].kind;
  return k == EmitterKind::Area || k == EmitterKind::Point;
}

bool bidirectionalApplies(const uint8_t* kinds, int n) {
  if (n < 2 || n > kMaxChainVertices) return false;
  for (int j = 0; j < n; ++j)
    if (kinds[j] == kTailVertex) return false;
  return true;
}

namespace {

// The deletion's weight by the number of deleted edges kd (Veach: short deletions first).
double deletionWeight(int kd) { return kd == 1 ? 0.25 : kd == 2 ? 0.5 : std::ldexp(1.0, -kd); }

// The vertex m may reach: the light vertex's successor n when the light may be deleted.
int lastDeletable(int n, bool lightDeletable) { return lightDeletable ? n : n - 1; }

// How many l in [0, n - 2] have l + kd <= mMax.
int positions(int n, int mMax, int kd) { return std::max(0, std::min(n - 2, mMax - kd) + 1); }

double deletionNorm(int n, int mMax) {
  double z = 0;
  for (int kd = 1; kd <= mMax; ++kd)
    if (positions(n, mMax, kd) > 0) z += deletionWeight(kd);
  return z;
}

// The range of added counts after deleting (l, m) from an n-vertex path.
void addedRange(int n, VertexRange lengths, int l, int m, int& lo, int& hi) {
  const int kept = n - (m - l - 1);
  lo = std::max(eyeSideMin(l) + (m == n ? 1 : 0), lengths.min - kept);
  hi = lengths.max - kept;
}

double additionWeight(int added, int deleted) { return std::ldexp(1.0, -std::abs(added - deleted)); }

bool isLight(const PathVertex& v) { return v.kind == kLightVertex || v.kind == kEnvironmentVertex; }

// The solid-angle density of BSDF sampling at v (arriving from wi) taking wo: a Dirac lobe's
// pick probability at a specular vertex; 0 at a light or eye vertex.
double samplingDensity(const MeasureContext& c, const PathVertex& v, Vec3 wi, Vec3 wo) {
  if (v.kind == kNonSpecularVertex) return factors::pdfAt(c, v, wi, wo);
  Color value;
  float probability;
  return v.kind == kSpecularVertex && factors::specularLobeAt(c, v, wi, wo, value, probability) ? probability : 0.0;
}

// Density (the mutation's measure) of vertex j sampled by the eye-side walk from vertex j - 1.
double eyeSideDensity(const MeasureContext& c, const PathVertex* path, int j) {
  if (j == 1) return 1.0 / (double(c.film.width()) * double(c.film.height()));  // a film position
  const PathVertex& v = path[j - 1];
  const double pdf = samplingDensity(c, v, directionBetween(v, path[j - 2]), directionBetween(v, path[j]));
  return pdf * double(factors::areaFactor(c, v, path[j]));
}

// Density of vertex j sampled by the light-side walk: from vertex j + 1 (its emission
// direction when it is the light), or, for a replaced light, the light point itself.
double lightSideDensity(const MeasureContext& c, const PathVertex* path, int n, int j, bool lightReplaced) {
  if (j == n - 1) return lightReplaced && path[j].kind == kLightVertex ? c.lights.emissionPositionDensity(path[j].emitter) : 0.0;
  const PathVertex& w = path[j + 1];
  const Vec3 wo = directionBetween(w, path[j]);
  double pdf = 0;
  if (j + 1 == n - 1) {
    if (w.kind != kLightVertex) return 0.0;  // the environment is never walked from
    pdf = c.lights.emissionDirectionDensity(w.emitter, w.ng, wo);
  } else {
    pdf = samplingDensity(c, w, directionBetween(w, path[j + 2]), wo);
  }
  return pdf * double(factors::areaFactor(c, w, path[j]));
}

}  // namespace

int eyeSideMin(int l) { return l == 0 ? 1 : 0; }
int eyeSideMax(int n, int m, int added) { return added - (m == n ? 1 : 0); }

double deletionProbability(int n, bool lightDeletable, int l, int m) {
  const int mMax = lastDeletable(n, lightDeletable), kd = m - l;
  if (l < 0 || l > n - 2 || kd < 1 || m > mMax) return 0.0;
  return deletionWeight(kd) / deletionNorm(n, mMax) / positions(n, mMax, kd);
}

double additionProbability(int n, VertexRange lengths, int l, int m, int added) {
  int lo, hi;
  addedRange(n, lengths, l, m, lo, hi);
  if (added < lo || added > hi) return 0.0;
  const int deleted = m - l - 1;
  double z = 0;
  for (int a = lo; a <= hi; ++a) z += additionWeight(a, deleted);
  return additionWeight(added, deleted) / z;
}

bool drawBidirectionalPlan(int n, bool lightDeletable, VertexRange lengths, uint64_t key, uint32_t dim,
                           BidirectionalPlan& out) {
  if (n < 2) return false;
  const int mMax = lastDeletable(n, lightDeletable);
  // kd by its weight (53-bit coin), then l uniform among its positions (exact index).
  double u = uniformDouble(key, dim) * deletionNorm(n, mMax);
  int kd = 0;
  for (int k = 1; k <= mMax; ++k) {
    if (positions(n, mMax, k) == 0) continue;
    kd = k;
    if ((u -= deletionWeight(k)) < 0) break;
  }
  if (kd == 0) return false;
  out.l = int(uniformIndex(key, dim + 1, uint64_t(positions(n, mMax, kd))));
  out.m = out.l + kd;
  int lo, hi;
  addedRange(n, lengths, out.l, out.m, lo, hi);
  if (hi < lo) return false;
  const int deleted = out.deleted();
  double z = 0;
  for (int a = lo; a <= hi; ++a) z += additionWeight(a, deleted);
  u = uniformDouble(key, dim + 2) * z;
  out.added = hi;
  for (int a = lo; a <= hi; ++a)
    if ((u -= additionWeight(a, deleted)) < 0) {
      out.added = a;
      break;
    }
  const int tMin = eyeSideMin(out.l), tMax = eyeSideMax(n, out.m, out.added);
  if (tMax < tMin) return false;
  out.eyeSide = tMin + int(uniformIndex(key, dim + 3, uint64_t(tMax - tMin + 1)));
  return true;
}

Color bidirectionalContribution(const MeasureContext& c, const PathVertex* path, int n, float filmX, float filmY) {
  if (n < 2 || !isLight(path[n - 1])) return Color(0.0f);
  Color f(c.film.density(filmX, filmY));
  for (int j = 1; j < n - 1; ++j) {
    const PathVertex& v = path[j];
    const Vec3 wi = directionBetween(v, path[j - 1]), wo = directionBetween(v, path[j + 1]);
    if (v.kind == kSpecularVertex)
      f *= factors::specularAt(c, v, wi, wo, false);
    else if (v.kind == kNonSpecularVertex)
      f *= factors::evalAt(c, v, wi, wo);
    else
      return Color(0.0f);
    if (j >= 2) f *= factors::areaFactor(c, path[j - 1], v);  // vertex 1 is in film measure
  }
  const PathVertex& light = path[n - 1];
  if (n >= 3) f *= factors::areaFactor(c, path[n - 2], light);
  return f * factors::emittedAlong(c, light, directionBetween(light, path[n - 2]));
}

double regeneratedDensity(const MeasureContext& c, const PathVertex* path, int n, int l, int added, bool lightReplaced) {
  double eye[kMaxChainVertices + 1], light[kMaxChainVertices + 1];
  for (int i = 1; i <= added; ++i) {
    eye[i] = eyeSideDensity(c, path, l + i);
    light[i] = lightSideDensity(c, path, n, l + i, lightReplaced);
  }
  const int tMin = eyeSideMin(l), tMax = added - (lightReplaced ? 1 : 0);
  if (tMax < tMin) return 0.0;
  double sum = 0;
  for (int t = tMin; t <= tMax; ++t) {
    // The connection joins vertex l + t (a non-specular surface) to l + t + 1 (a non-specular
    // surface or a light).
    const PathVertex &e = path[l + t], &lv = path[l + t + 1];
    if (e.kind != kNonSpecularVertex || !(lv.kind == kNonSpecularVertex || isLight(lv))) continue;
    double p = 1;
    for (int i = 1; i <= t; ++i) p *= eye[i];
    for (int i = t + 1; i <= added; ++i) p *= light[i];
    if (std::isfinite(p)) sum += p;
  }
  return sum / double(tMax - tMin + 1);
}

double bidirectionalTransition(const MeasureContext& c, VertexRange lengths, const PathVertex* y, int ny, int l, int m,
                               const PathVertex* z, int nz, int added) {
  const double choice = deletionProbability(ny, lightDeletable(c, y, ny), l, m) *
                        additionProbability(ny, lengths, l, m, added);
  return choice > 0 ? choice * regeneratedDensity(c, z, nz, l, added, m == ny) : 0.0;
}

double bidirectionalRatio(const MeasureContext& c, VertexRange lengths, const PathVertex* y, int ny, float yFilmX,
                          float yFilmY, const PathVertex* z, int nz, float zFilmX, float zFilmY,
                          const BidirectionalPlan& plan) {
  const double fy = luminance(bidirectionalContribution(c, y, ny, yFilmX, yFilmY));
  const double fz = luminance(bidirectionalContribution(c, z, nz, zFilmX, zFilmY));
  const double forward = bidirectionalTransition(c, lengths, y, ny, plan.l, plan.m, z, nz, plan.added);
  const double reverse =
      bidirectionalTransition(c, lengths, z, nz, plan.l, plan.l + plan.added + 1, y, ny, plan.deleted());
  if (!(fy > 0) || !(forward > 0) || !(reverse > 0)) return 0.0;
  const double r = fz * reverse / (fy * forward);
  return std::isfinite(r) ? r : 0.0;
}

// The unit for the accept stage: the stage that made the proposal computed its ratio
// (proposals.ratio); moving the chain copies the whole proposed path.
namespace {
Acceptance bidirectionalAcceptance(const StepConfig&, const AcceptSlot& s) {
  Acceptance a;
  a.q = float(std::min(1.0, double(s.proposals.ratio[s.i]) * double(s.proposals.selection[s.i])));
  a.fz = s.proposals.colorAt(s.i);
  return a;
}

bool appliesToSignature(const uint8_t* kinds, int n) { return bidirectionalApplies(kinds, n); }
int noTail(const uint8_t*, int n) { return n; }
}  // namespace

extern const Mutation kBidirectionalMutation{MutationKind::Bidirectional, MutationKind::Bidirectional,
                                             appliesToSignature, /*startRange=*/nullptr, noTail,
                                             /*contribution=*/nullptr, /*transitionRatio=*/nullptr,
                                             bidirectionalAcceptance, moveToWholePath};

}  // namespace erpt
