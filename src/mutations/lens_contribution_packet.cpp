// The lens contribution packet (lens_contribution_packet.h): which proposals it takes, and
// lensContribution's arithmetic for them over lanes. Each formula mirrors the scalar code it
// replaces for these paths: directionBetween, evalAt with the diffuse lobe of bsdfEval
// (sideFlip, evalFront), areaFactor and emittedAlong of an area light, and the cached tail.
#include "mutations/lens_contribution_packet.h"

#include <xsimd/xsimd.hpp>

#include "kernels/lane_gather.h"
#include "kernels/lane_vec3.h"

namespace erpt {

namespace {

using namespace lanes3;
constexpr size_t kLanes = batch::size;
static_assert(LensContributionPacket::kCapacity % kLanes == 0, "a packet is whole batches");

// An untextured diffuse material: its reflectance and sidedness are all evalAt reads.
const Material* plainDiffuse(const Scene& scene, int32_t material) {
  if (material < 0) return nullptr;
  const Material& m = scene.materials[size_t(material)];
  return m.kind == BsdfKind::Diffuse && m.reflectance.texture < 0 ? &m : nullptr;
}

// normalize() of math.h: v times the reciprocal of its length.
V3 normalized(const V3& v) { return v * (batch(1.0f) / xsimd::sqrt(dot(v, v))); }

// f(wi, wo) |cos wo| of the diffuse lobe around the shading normal n (bsdfEval: sideFlip, then
// evalFront), with the scalar code's comparisons, so NaNs go where they go there.
V3 diffuseEval(const V3& reflectance, const batch& twoSided, const V3& n, const V3& wi, const V3& wo) {
  const batch wiZ = dot(wi, n), woZ = dot(wo, n);
  const batch flip = xsimd::select(wiZ > batch(0.0f), batch(1.0f),
                                   xsimd::select((twoSided != batch(0.0f)) & (wiZ < batch(0.0f)), batch(-1.0f),
                                                 batch(0.0f)));
  const batch inZ = wiZ * flip, outZ = woZ * flip;
  const mask lit = (flip != batch(0.0f)) & !(inZ <= batch(0.0f)) & !(outZ <= batch(0.0f));
  const V3 zero{batch(0.0f), batch(0.0f), batch(0.0f)};
  return select(lit, reflectance * (outZ * kInvPi), zero);
}

}  // namespace

bool LensContributionPacket::qualifies(const StepConfig& ctx, const ChainQueue& chains,
                                       const VertexQueue& chainVertices, const ProposalQueue& proposals,
                                       const VertexQueue& proposalVertices, size_t i) {
  if (chains.stepsLeft[i] == 0 || proposals.state[i] != kProposalComplete) return false;
  const Mutation& unit = mutationOf(MutationKind(proposals.mutation[i]));
  if (unit.contribution != lensContribution || unit.acceptance != perturbationAcceptance) return false;
  // lum(f(y)) cached in this measure (after a chain's first lens step, always).
  const uint8_t measure = uint8_t(unit.measure);
  if (chains.fKind[i] != measure) return false;
  if (proposals.regenFirst[i] != 1 || proposals.regenLast[i] != 1) return false;
  const int n = chains.vertexCount[i];
  const uint64_t signature = chains.signature[i];
  const size_t row = i * kMaxChainVertices;
  if (n < 3 || kindAt(signature, 0) != kEyeVertex || proposalVertices.kind[row + 1] != kNonSpecularVertex) return false;
  const Scene& scene = ctx.measure.scene;
  const Material* first = plainDiffuse(scene, proposalVertices.material[row + 1]);
  if (!first) return false;
  const uint8_t secondKind = kindAt(signature, 2);
  const size_t j = count_;
  if (secondKind == kLightVertex) {
    const int32_t e = chainVertices.emitter[row + 2];
    if (e < 0 || scene.emitters[size_t(e)].kind != EmitterKind::Area) return false;
    const Color radiance = scene.emitters[size_t(e)].radiance;
    in_[kR2][j] = radiance.x, in_[kG2][j] = radiance.y, in_[kB2][j] = radiance.z;
    in_[kTwoSided2][j] = 0;
    in_[kLight2][j] = 1;
  } else {
    // A diffuse vertex 2 followed by a vertex whose position f reads (not the environment),
    // and the fixed tail from there cached (a path that ends at vertex 2 has none).
    if (secondKind != kNonSpecularVertex || n < 4 || kindAt(signature, 3) == kEnvironmentVertex ||
        chains.tailKind[i] != measure)
      return false;
    const Material* second = plainDiffuse(scene, chainVertices.material[row + 2]);
    if (!second) return false;
    in_[kR2][j] = second->reflectance.value.x, in_[kG2][j] = second->reflectance.value.y;
    in_[kB2][j] = second->reflectance.value.z;
    in_[kTwoSided2][j] = second->twoSided ? 1.0f : 0.0f;
    in_[kLight2][j] = 0;
  }
  in_[kR1][j] = first->reflectance.value.x, in_[kG1][j] = first->reflectance.value.y;
  in_[kB1][j] = first->reflectance.value.z;
  in_[kTwoSided1][j] = first->twoSided ? 1.0f : 0.0f;
  in_[kDensity][j] = ctx.measure.film.density(proposals.filmX[i], proposals.filmY[i]);
  slot_[j] = int32_t(i);
  vertexRow_[j] = int32_t(row);
  return true;
}

void LensContributionPacket::evaluate(const StepConfig& ctx, const ChainQueue& chains,
                                      const VertexQueue& chainVertices, const ProposalQueue& proposals,
                                      const VertexQueue& proposalVertices, size_t begin, size_t count) {
  begin_ = begin;
  count_ = 0;
  for (size_t r = 0; r < count; ++r)
    row_[r] = qualifies(ctx, chains, chainVertices, proposals, proposalVertices, begin + r) ? int32_t(count_++) : -1;
  // Rows past count_, up to a whole batch, gather row 0's entries: computed, never read.
  for (size_t j = count_; j % kLanes != 0; ++j) slot_[j] = slot_[0], vertexRow_[j] = vertexRow_[0];
  auto gather3 = [](const auto& x, const auto& y, const auto& z, const indices& at) {
    return V3{gatherLanes(x.data(), at), gatherLanes(y.data(), at), gatherLanes(z.data(), at)};
  };
  const VertexQueue& cv = chainVertices;
  for (size_t j = 0; j < count_; j += kLanes) {
    auto get = [&](int c) { return batch::load_aligned(&in_[c][j]); };
    const indices slot = indices::load_aligned(&slot_[j]), row = indices::load_aligned(&vertexRow_[j]);
    // z: the eye and vertices 2, 3 are the current path's, vertex 1 the proposal's.
    const V3 p0 = gather3(cv.pX, cv.pY, cv.pZ, row);
    const V3 p1 = gather3(proposalVertices.pX, proposalVertices.pY, proposalVertices.pZ, row + 1);
    const V3 ns1 = gather3(proposalVertices.nsX, proposalVertices.nsY, proposalVertices.nsZ, row + 1);
    const V3 p2 = gather3(cv.pX, cv.pY, cv.pZ, row + 2), ng2 = gather3(cv.ngX, cv.ngY, cv.ngZ, row + 2);

    const batch density = get(kDensity);
    const V3 toPrev = normalized(p0 - p1), toNext = normalized(p2 - p1);
    V3 f = V3{density, density, density} *
           diffuseEval({get(kR1), get(kG1), get(kB1)}, get(kTwoSided1), ns1, toPrev, toNext);
    const V3 d = p2 - p1;  // areaFactor(vertex 1, vertex 2)
    const batch dist2 = dot(d, d);
    f = f * (xsimd::abs(dot(ng2, d)) / (dist2 * xsimd::sqrt(dist2)));
    const V3 colour2{get(kR2), get(kG2), get(kB2)};
    const V3 zero{batch(0.0f), batch(0.0f), batch(0.0f)};
    const V3 toFirst = -toNext;
    // Vertex 2 a light: its radiance towards vertex 1 (one-sided, emittedAlong).
    const V3 viaLight = f * select(dot(ng2, toFirst) <= batch(0.0f), zero, colour2);
    // Vertex 2 diffuse: its BSDF between vertex 1 and vertex 3, then the cached tail.
    V3 viaSurface = viaLight;
    const mask light = get(kLight2) != batch(0.0f);
    if (!xsimd::all(light)) {
      const V3 p3 = gather3(cv.pX, cv.pY, cv.pZ, row + 3), ns2 = gather3(cv.nsX, cv.nsY, cv.nsZ, row + 2);
      const V3 tail = gather3(chains.tailR, chains.tailG, chains.tailB, slot);
      viaSurface = f * diffuseEval(colour2, get(kTwoSided2), ns2, toFirst, normalized(p3 - p2)) * tail;
    }
    // A film position of zero density ends f before anything else.
    const V3 fz = select(density == batch(0.0f), zero, select(light, viaLight, viaSurface));
    fz.x.store_aligned(&out_[kFr][j]);
    fz.y.store_aligned(&out_[kFg][j]);
    fz.z.store_aligned(&out_[kFb][j]);
  }
}

}  // namespace erpt
