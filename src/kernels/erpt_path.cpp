// Path signatures, mutation choice and the perturbation sampler of ERPT.
#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>

#include "kernels/erpt_path.h"
#include "core/warp.h"

namespace erpt {

const char* rejectReasonName(RejectReason r) {
  switch (r) {
    case kRejectNone: return "none";
    case kRejectNoMutation: return "no mutation applies";
    case kRejectOffFilm: return "off the film";
    case kRejectMissed: return "ray missed";
    case kRejectKindChanged: return "vertex kind changed";
    case kRejectOccluded: return "connection occluded";
    case kRejectZero: return "zero contribution";
    case kRejectIrreversible: return "reverse move impossible";
    case kRejectCurrentZero: return "current path zero in this measure";
    case kRejectByChance: return "not accepted (q)";
    case kRejectNoCandidate: return "large step made no such path";
    case kRejectOutsideDomain: return "large step outside the chains' paths";
    case kRejectNoWalk: return "manifold walk did not converge";
    default: return "?";
  }
}

const char* mutationName(MutationKind k) {
  switch (k) {
    case MutationKind::None: return "none";
    case MutationKind::Lens: return "lens";
    case MutationKind::LensDisk: return "lens (disk)";
    case MutationKind::Caustic: return "caustic";
    case MutationKind::CausticVeach: return "caustic (Veach angle)";
    case MutationKind::LargeStep: return "large step";
    case MutationKind::Bidirectional: return "bidirectional";
    case MutationKind::Manifold: return "manifold";
    default: return "?";
  }
}

const char* inPlaceReasonName(InPlaceReason r) {
  switch (r) {
    case kInPlaceNoMutation: return "no mutation applies";
    case kInPlaceZeroContribution: return "zero or non-finite f";
    case kInPlaceNoDepositEnergy: return "no deposition energy (e_d = 0)";
    case kInPlaceDirectionalLight: return "directional light";
    case kInPlaceFoldedChain: return "too long: folded tail, nothing before it moves";
    case kInPlaceTooLong: return "too long for a chain";
    case kInPlaceOutsideLargeStep: return "no large step makes it";
    default: return "?";
  }
}

Vec3 directionBetween(const PathVertex& a, const PathVertex& b) {
  // An environment vertex stores the direction it is seen in as -normal.
  if (b.kind == kEnvironmentVertex) return -b.ns;
  return normalize(b.p - a.p);
}

bool reflectsAt(const PathVertex* path, int j) {
  const Vec3 n = path[j].ng;
  return dot(directionBetween(path[j], path[j - 1]), n) * dot(directionBetween(path[j], path[j + 1]), n) > 0;
}

uint64_t packSignature(const uint8_t* kinds, int n) {
  uint64_t s = 0;
  for (int j = 0; j < n && j < kMaxChainVertices; ++j) s |= uint64_t(kinds[j]) << (kSignatureBitsPerVertex * j);
  return s;
}

uint32_t chainsForSeed(double energy, double chainLength, double depositEnergy, double u) {
  const double expected = energy / (chainLength * depositEnergy);
  if (!(expected >= 0)) return 0;
  return uint32_t(std::min(double(UINT32_MAX), std::floor(u + expected)));
}

Vec3 perturbDirection(Vec3 d, float u1, float u2) {
  // theta = theta_max * (theta_min / theta_max)^u1: density proportional to 1 / theta.
  const float theta = kPerturbThetaMax * std::exp(std::log(kPerturbThetaMin / kPerturbThetaMax) * u1);
  const float phi = 2 * kPi * u2;
  Frame f(d);
  const float st = std::sin(theta);
  return normalize(f.toWorld(Vec3{st * std::cos(phi), st * std::sin(phi), std::cos(theta)}));
}

}  // namespace erpt
