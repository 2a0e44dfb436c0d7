// The caustic perturbation (ERPT paper section 4.3, after Veach and Guibas 1997): the
// direction leaving the source vertex s (the light, or the second non-specular vertex) is
// perturbed by an angle theta around the current one (azimuth uniform), the ray follows the
// current path's specular lobes back to vertex 1, which connects to the eye.
//   ERPT:  theta with density proportional to 1/theta on [1e-4, 0.1] rad. The density of the
//          new direction (solid angle) depends on theta only, which is the same both ways:
//          T(z -> y) / T(y -> z) = 1.
//   Veach: theta uniform in [0, theta_max(y)] (PMC-ER eq. 6), solid-angle density
//          1 / (2 pi theta_max(y) sin theta). theta_max depends on the path, so
//          T(z -> y) / T(y -> z) = theta_max(y) / theta_max(z), and 0 when theta exceeds
//          theta_max(z) (z could not propose y).
#include <algorithm>
#include <cmath>

#include "mutations/mutation.h"
#include "models/surface.h"
#include "path_factors.h"
#include "start_each.h"

namespace erpt {

int causticSource(const uint8_t* kinds, int n) {
  if (n < 3 || kinds[1] != kNonSpecularVertex) return -1;
  int s = 2;
  while (s < n && kinds[s] == kSpecularVertex) ++s;
  if (s >= n || kinds[s] == kEnvironmentVertex || kinds[s] == kTailVertex) return -1;
  return s;
}

bool isCausticPath(const uint8_t* kinds, int n) {
  return n >= 4 && kinds[1] == kNonSpecularVertex && kinds[2] == kSpecularVertex && causticSource(kinds, n) > 0;
}

Color causticContribution(const MeasureContext& c, const PathVertex* path, int n, float filmX, float filmY,
                          FixedTail* tail) {
  uint8_t kinds[kMaxChainVertices];
  if (n > kMaxChainVertices) return Color(0.0f);
  for (int j = 0; j < n; ++j) kinds[j] = path[j].kind;
  const int s = causticSource(kinds, n);
  if (s < 0) return Color(0.0f);
  const float h = c.film.density(filmX, filmY);
  const PathVertex& v1 = path[1];
  const Vec3 toEye = path[0].p - v1.p;  // the eye: the pinhole, or the chain's lens point
  const float dist2 = dot(toEye, toEye);
  const Vec3 wEye = toEye / std::sqrt(dist2);
  const float cosAxis = c.camera.cosToAxis(-wEye);
  if (!(h > 0) || !(cosAxis > 0)) return Color(0.0f);
  // Film area (pixels^2) per unit area at v1 (density rule 5), then v1's BSDF: the cosine towards the
  // light side is shading-normal; the geometric one cancels against the specular chain's
  // etendue (docs/erpt-acceptance.md).
  const Vec3 toV2 = directionBetween(v1, path[2]);
  const float cosG1 = std::abs(dot(v1.ng, toV2));
  if (!(cosG1 > 0)) return Color(0.0f);
  const float pixelScale = c.camera.pixelsPerPlaneUnit();
  Color f = factors::evalAt(c, v1, wEye, toV2) * (h * pixelScale * pixelScale * std::abs(dot(v1.ng, wEye)) /
                                         (dist2 * cosAxis * cosAxis * cosAxis * cosG1));
  for (int j = 2; j < s; ++j)
    f *= factors::specularAt(c, path[j], directionBetween(path[j], path[j - 1]), directionBetween(path[j], path[j + 1]), true);
  const PathVertex& src = path[s];
  const Vec3 ws = directionBetween(src, path[s - 1]);
  if (factors::isPointLight(c, src)) return f * factors::emittedAlong(c, src, ws);
  const float cosS = std::abs(dot(src.ng, ws));
  if (src.kind == kLightVertex) return f * factors::emittedAlong(c, src, ws) * cosS;
  if (s + 1 >= n) return Color(0.0f);
  return f * factors::evalAt(c, src, ws, directionBetween(src, path[s + 1])) * cosS * factors::tailFrom(c, path, n, s + 1, tail);
}


float causticThetaMax(const MeasureContext& c, const CurrentPath& y, float pixels) {
  const int s = causticSource(y.kinds, y.n);
  if (s < 0) return 0;
  double toSource = 0;
  for (int k = 2; k <= s; ++k) toSource += double(length(y.vertices[k].p - y.vertices[k - 1].p));
  const double eyeSegment = double(length(y.vertices[1].p - y.vertices[0].p));
  const double thetaPixels = std::atan(double(pixels) / double(c.camera.pixelsPerPlaneUnit()));
  // At most pi: uniform theta in [0, pi] already covers the sphere of directions; beyond it
  // theta would wrap around and the density 1 / (2 pi theta_max sin theta) would no longer
  // be the density of the direction (large radii with a long eye segment and a short source
  // segment, e.g. PMC-ER's 50 pixels, reach it).
  return toSource > 0 ? float(std::min(double(kPi), thetaPixels * eyeSegment / toSource)) : 0.0f;
}

namespace {

bool appliesToCausticPaths(const uint8_t* kinds, int n) { return n <= kMaxChainVertices && causticSource(kinds, n) > 0; }

int causticTailStart(const uint8_t* kinds, int n) {
  const int s = causticSource(kinds, n);
  return s < 0 ? n : std::min(n, s + 1);
}

// Unit direction from the source towards vertex s - 1.
Vec3 sourceDirection(const CurrentPath& y, int s) { return directionBetween(y.vertices[s], y.vertices[s - 1]); }

// The start around a perturbed source direction d.
void startAlong(const MeasureContext& c, const CurrentPath& y, int s, Vec3 d, ProposalStart& out) {
  const PathVertex& src = y.vertices[s];
  out.origin = factors::isPointLight(c, src) ? src.p : offsetOrigin(src.p, src.ng, d);
  out.direction = d;
  out.tnear = 0;
  out.tfar = std::numeric_limits<float>::infinity();
  out.cursor = s - 1;
  out.walk = -1;
  out.regenFirst = 1;
  out.regenLast = s - 1;
  out.connectTo = 0;
}

void startErpt(const MeasureContext& c, const CurrentPath& y, float, float, float, float u1, float u2, ProposalStart& out) {
  const int s = causticSource(y.kinds, y.n);
  startAlong(c, y, s, perturbDirection(sourceDirection(y, s), u1, u2), out);
}

void startVeach(const MeasureContext& c, const CurrentPath& y, float, float, float size, float u1, float u2,
                ProposalStart& out) {
  const int s = causticSource(y.kinds, y.n);
  const float thetaMax = causticThetaMax(c, y, size);
  if (!(thetaMax > 0)) {
    out.reject = kRejectZero;
    return;
  }
  const float theta = std::min(thetaMax, u1 * thetaMax), phi = 2 * kPi * u2;
  const Frame f(sourceDirection(y, s));
  const float st = std::sin(theta);
  startAlong(c, y, s, normalize(f.toWorld(Vec3{st * std::cos(phi), st * std::sin(phi), std::cos(theta)})), out);
}

void startErptRange(const StepConfig& ctx, const ChainQueue& chains, const VertexQueue& chainVertices,
                    ProposalQueue& proposals, RayQueue& rays, IndexRange range) {
  startEach<startErpt>(MutationKind::Caustic, ctx, chains, chainVertices, proposals, rays, range);
}

void startVeachRange(const StepConfig& ctx, const ChainQueue& chains, const VertexQueue& chainVertices,
                     ProposalQueue& proposals, RayQueue& rays, IndexRange range) {
  startEach<startVeach>(MutationKind::CausticVeach, ctx, chains, chainVertices, proposals, rays, range);
}

float erptRatio(const MeasureContext&, const CurrentPath&, const CurrentPath&, float) {
  // p(theta) / (2 pi sin theta) both ways, at the same theta.
  return 1.0f;
}

float veachRatio(const MeasureContext& c, const CurrentPath& y, const CurrentPath& z, float size) {
  const int s = causticSource(y.kinds, y.n);
  const float maxY = causticThetaMax(c, y, size), maxZ = causticThetaMax(c, z, size);
  if (!(maxY > 0) || !(maxZ > 0)) return 0;
  const double cosTheta = std::clamp(double(dot(sourceDirection(y, s), sourceDirection(z, s))), -1.0, 1.0);
  // Rounding of the traced vertex s - 1 may put theta a hair beyond theta_max(y).
  if (std::acos(cosTheta) > double(maxZ) * (1 + 1e-4)) return 0;
  return maxY / maxZ;
}

}  // namespace

extern const Mutation kCausticMutation{MutationKind::Caustic, MutationKind::Caustic, appliesToCausticPaths, startErptRange,
                                       causticTailStart, causticContribution, erptRatio, perturbationAcceptance, moveToPerturbation};
extern const Mutation kCausticVeachMutation{MutationKind::CausticVeach, MutationKind::Caustic, appliesToCausticPaths,
                                            startVeachRange, causticTailStart, causticContribution, veachRatio,
                                            perturbationAcceptance, moveToPerturbation};

}  // namespace erpt
