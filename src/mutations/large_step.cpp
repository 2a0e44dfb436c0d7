// MLT's large step: the path tracer's density of a given path (large_step.h, docs/mlt.md).
// The terms follow the path tracer's sampling decisions vertex by vertex (stages.h:
// stageShadePath, connectToLight): BSDF sampling with its lobe choice, Russian roulette from
// depth rrDepth on (survival min(0.95, max component of the throughput times eta^2)), and the light
// sampler's density for the next-event connection.
#include "mutations/large_step.h"

#include <algorithm>
#include <cmath>

#include "models/bsdf.h"
#include "mutations/mutation.h"
#include "path_factors.h"

namespace erpt {

void LargeStepModel::setLengths(const double* energyByLength, const double* neeEnergyByLength) {
  constexpr double kUniform = 0.3, kMinTechnique = 0.1;
  double total = 0;
  for (int n = minVertices; n <= maxVertices; ++n) total += energyByLength[n];
  const int lengths = maxVertices - minVertices + 1;
  for (int n = 0; n <= kMaxChainVertices; ++n) {
    neeShare[n] = 0.5f;
    if (n < minVertices || n > maxVertices) {
      lengthProbability[n] = 0;
      continue;
    }
    const double byEnergy = total > 0 ? energyByLength[n] / total : 1.0 / lengths;
    lengthProbability[n] = float((1 - kUniform) * byEnergy + kUniform / lengths);
    if (neeEnergyByLength && energyByLength[n] > 0)
      neeShare[n] = float(std::clamp(neeEnergyByLength[n] / energyByLength[n], kMinTechnique, 1 - kMinTechnique));
  }
}

namespace {

// The light sampler's density of picking `light` from `from` (its own measure).
float neeDensity(const MeasureContext& c, const PathVertex& from, const PathVertex& light) {
  if (light.emitter < 0) return 0.0f;
  switch (c.scene.emitters[size_t(light.emitter)].kind) {
    case EmitterKind::Point: return c.lights.pickProbabilityOfEmitter(light.emitter);
    case EmitterKind::Constant: return c.lights.pdfEnvironment(directionBetween(from, light));
    case EmitterKind::Area: return c.lights.pdfAreaOfEmitter(light.emitter, from.p, light.p, light.ng);
    case EmitterKind::Directional: return 0.0f;  // not in the chains' paths (seed_checks.h)
  }
  return 0.0f;
}

// The path tracer's Russian roulette at depth `depth` with throughput `next` after the bounce
// and the squared IORs crossed up to it: the survival probability (1 before rrDepth).
float survival(int depth, int rrDepth, const Color& next, float etaSquared) {
  return depth >= rrDepth ? russianRouletteSurvival(next, etaSquared) : 1.0f;
}

}  // namespace

bool largeStepTerms(const MeasureContext& c, int rrDepth, const PathVertex* path, int n, LargeStepTerms& out) {
  out = LargeStepTerms{};
  if (n < 2) return false;
  const PathVertex& light = path[n - 1];
  if (light.kind != kLightVertex && light.kind != kEnvironmentVertex) return false;
  const Color emitted = factors::emittedAlong(c, light, directionBetween(light, path[n - 2]));
  if (n == 2) {
    // An emitter the camera ray hits: the camera's own sample, throughput 1.
    out.value = emitted;
    out.pHit = 1;
    return !isBlack(emitted);
  }
  Color throughput(1.0f);
  float etaSquared = 1;
  for (int j = 1; j <= n - 2; ++j) {
    const PathVertex& v = path[j];
    const Vec3 wi = directionBetween(v, path[j - 1]), wo = directionBetween(v, path[j + 1]);
    Color f;
    float pdf = 0;
    const bool specular = v.kind == kSpecularVertex;
    if (specular) {
      if (!factors::specularLobeAt(c, v, wi, wo, f, pdf)) return false;
    } else {
      f = factors::evalAt(c, v, wi, wo);
      pdf = factors::pdfAt(c, v, wi, wo);
    }
    if (isBlack(f)) return false;
    const float eta = factors::etaAt(c, v, wi, wo);
    etaSquared *= eta * eta;
    if (j < n - 2) {
      // Depth j: the BSDF sampled the direction to vertex j + 1, then the roulette let it go on.
      if (!(pdf > 0)) return false;
      const Color next = throughput * f / pdf;
      throughput = next / survival(j, rrDepth, next, etaSquared);
      continue;
    }
    // The last surface vertex: f, the light's emission and the last segment's area factor.
    const float area = factors::areaFactor(c, v, light);
    out.value = throughput * f * emitted * area;
    const bool deltaLight = factors::isPointLight(c, light);
    if (pdf > 0 && !deltaLight) out.pHit = pdf * area * survival(j, rrDepth, throughput * f / pdf, etaSquared);
    if (!specular) out.pNee = neeDensity(c, v, light);
  }
  return !isBlack(out.value) && (out.pHit > 0 || out.pNee > 0);
}

float largeStepWeight(const MeasureContext& c, const LargeStepModel& m, const PathVertex* path, int n) {
  if (n < m.minVertices || n > m.maxVertices) return 0.0f;
  LargeStepTerms t;
  if (!largeStepTerms(c, m.rrDepth, path, n, t)) return 0.0f;
  const float pNee = m.neeProbability(n);
  const float q = m.lengthProbability[n] * ((1 - pNee) * t.pHit + pNee * t.pNee);
  const float w = luminance(t.value) / q;
  return q > 0 && std::isfinite(w) && w > 0 ? w : 0.0f;
}

// The large step as a mutation unit (mutation.h). Its proposals are not started by the unit:
// MLT's ProposalPolicy traces them as path-tracer samples (mlt_integrator.cpp); it has no
// f of its own measure (W compares the path tracer's estimates) and no transition ratio (its
// density does not depend on y).
namespace {
// q = min(1, W(z) / W(y)). W(y) is cached with the chain until a perturbation moves it.
Acceptance largeStepAcceptance(const StepConfig& ctx, const AcceptSlot& s) {
  ChainQueue& chains = s.chains;
  const size_t i = s.i;
  Acceptance a;
  if (chains.largeWeight[i] < 0) {
    const int n = loadChainPath(chains, s.chainVertices, i, s.y);
    chains.largeWeight[i] = largeStepWeight(ctx.measure, *ctx.largeSteps, s.y, n);
  }
  const float wy = chains.largeWeight[i], wz = s.proposals.largeWeight[i];
  if (!(wy > 0) || !std::isfinite(wy)) {
    // q(y) = 0: no large step leads to y, so none may leave it either.
    s.proposals.reason[i] = kRejectIrreversible;
  } else {
    a.q = std::min(1.0f, wz / wy);
  }
  a.fz = s.proposals.colorAt(i);
  return a;
}

}  // namespace

// Moves the chain to a proposal that made its whole path (a large step, the bidirectional
// mutation): every vertex, its count and signature, and W(z) when the proposal knows it.
void moveToWholePath(const AcceptSlot& s, const Acceptance&) {
  ChainQueue& chains = s.chains;
  const ProposalQueue& proposals = s.proposals;
  const size_t i = s.i, base = i * kMaxChainVertices;
  for (int j = 0; j < proposals.vertexCount[i]; ++j)
    s.chainVertices.copyRow(base + size_t(j), s.proposalVertices, base + size_t(j));
  chains.vertexCount[i] = proposals.vertexCount[i];
  chains.signature[i] = proposals.signature[i];
  chains.largeWeight[i] = proposals.largeWeight[i];
  chains.fKind[i] = chains.tailKind[i] = uint8_t(MutationKind::None);  // f and the tail in no measure yet
}

namespace {

bool appliesToChainPaths(const uint8_t*, int n) { return n >= 2 && n <= kMaxChainVertices; }
int noTail(const uint8_t*, int n) { return n; }
}  // namespace

extern const Mutation kLargeStepMutation{MutationKind::LargeStep, MutationKind::LargeStep, appliesToChainPaths,
                                         /*startRange=*/nullptr, noTail, /*contribution=*/nullptr,
                                         /*transitionRatio=*/nullptr, largeStepAcceptance, moveToWholePath};

}  // namespace erpt
