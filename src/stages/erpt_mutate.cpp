// ERPT mutate stage: picks the mutation for each chain and emits the proposal's first ray.
#include <algorithm>

#include "erpt/erpt_stages.h"
#include "erpt/rng.h"
#include "erpt/surface.h"
#include "erpt/tracer.h"

namespace erpt {

ErptQueues::ErptQueues(size_t capacity) {
  chains.resize(capacity);
  proposals.resize(capacity);
  chainVertices.resize(capacity * kMaxChainVertices);
  proposalVertices.resize(capacity * kMaxChainVertices);
  prepareRays(rays, capacity);
  prepareRays(shadowRays, capacity);
  hits.resize(capacity);
  deposits.resize(capacity);
  for (size_t i = 0; i < capacity; ++i) chains.stepsLeft[i] = 0;
}

int loadChainPath(const ChainQueue& chains, const VertexQueue& vertices, size_t slot, PathVertex* out) {
  const int n = chains.vertexCount[slot];
  for (int j = 0; j < n; ++j) out[j] = loadVertex(vertices, slot * kMaxChainVertices + size_t(j));
  return n;
}

void loadChainFromSeed(ChainQueue& chains, VertexQueue& chainVertices, size_t slot, const SeedStore& store,
                       size_t seed, uint64_t key, uint32_t chainLength, float energyPerStep) {
  const SeedQueue& s = store.seeds;
  const uint32_t n = s.vertexCount[seed];
  for (uint32_t j = 0; j < n; ++j)
    chainVertices.copyRow(slot * kMaxChainVertices + j, store.vertices, s.vertexBegin[seed] + j);
  const Color c = store.contribution(seed);
  const Color color = c / luminance(c);
  chains.key[slot] = key;
  chains.step[slot] = 0;
  chains.stepsLeft[slot] = chainLength;
  chains.vertexCount[slot] = uint8_t(n);
  uint8_t kinds[kMaxChainVertices];
  for (uint32_t j = 0; j < n && j < uint32_t(kMaxChainVertices); ++j) kinds[j] = store.vertices.kind[s.vertexBegin[seed] + j];
  chains.signature[slot] = packSignature(kinds, int(std::min<uint32_t>(n, kMaxChainVertices)));
  chains.fKind[slot] = uint8_t(MutationKind::None);
  chains.fLum[slot] = 0;
  chains.tailKind[slot] = uint8_t(MutationKind::None);
  chains.filmX[slot] = s.filmX[seed];
  chains.filmY[slot] = s.filmY[seed];
  chains.colorR[slot] = color.x;
  chains.colorG[slot] = color.y;
  chains.colorB[slot] = color.z;
  chains.energy[slot] = energyPerStep;
  chains.runPixel[slot] = kNoPixel;
  chains.runLength[slot] = 0;
}

namespace {

void reject(ProposalQueue& p, RayQueue& rays, size_t i, RejectReason why) {
  p.state[i] = kProposalRejected;
  p.reason[i] = why;
  disableRay(rays, i);
}

}  // namespace

void stageErptMutate(const ErptStepContext& ctx, const ChainQueue& chains, const VertexQueue& chainVertices,
                     ProposalQueue& proposals, RayQueue& rays, IndexRange range) {
  const MeasureContext& mc = ctx.measure;
  uint8_t kinds[kMaxChainVertices];
  for (size_t i = range.begin; i < range.end; ++i) {
    proposals.mutation[i] = uint8_t(MutationKind::None);
    proposals.reason[i] = kRejectNone;
    proposals.connectTo[i] = -1;
    proposals.acceptance[i] = 0;
    if (chains.stepsLeft[i] == 0) {
      reject(proposals, rays, i, kRejectNone);
      continue;
    }
    const int n = chains.vertexCount[i];
    unpackSignature(chains.signature[i], n, kinds);
    const uint64_t key = chains.key[i];
    const uint32_t step = chains.step[i];
    const MutationKind kind = chooseMutation(ctx.strategy, kinds, n, uniformFloat(key, stepDim(step, kDimStrategy)));
    proposals.mutation[i] = uint8_t(kind);
    proposals.state[i] = kProposalWalking;
    const float u1 = uniformFloat(key, stepDim(step, kDimStart1)), u2 = uniformFloat(key, stepDim(step, kDimStart2));
    if (kind == MutationKind::Lens) {
      // Uniform in a square around the current film position: symmetric (rule 1).
      const float fx = chains.filmX[i] + (2 * u1 - 1) * ctx.lensRadius;
      const float fy = chains.filmY[i] + (2 * u2 - 1) * ctx.lensRadius;
      proposals.filmX[i] = fx;
      proposals.filmY[i] = fy;
      if (!(mc.film.density(fx, fy) > 0)) {
        reject(proposals, rays, i, kRejectOffFilm);
        continue;
      }
      const Camera::Ray r = mc.camera.generateRay(fx, fy);
      setRay(rays, i, r.origin, r.direction, r.tnear, r.tfar);
      proposals.cursor[i] = 1;
    } else if (kind == MutationKind::Caustic) {
      const int s = causticSource(kinds, n);
      const size_t base = i * kMaxChainVertices;
      const PathVertex src = loadVertex(chainVertices, base + size_t(s));
      const PathVertex towards = loadVertex(chainVertices, base + size_t(s - 1));
      const Vec3 d = perturbDirection(directionBetween(src, towards), u1, u2);
      const bool pointLight = src.kind == kLightVertex && src.emitter >= 0 &&
                              mc.scene.emitters[size_t(src.emitter)].kind == EmitterKind::Point;
      setRay(rays, i, pointLight ? src.p : offsetOrigin(src.p, src.ng, d), d, 0.0f,
             std::numeric_limits<float>::infinity());
      proposals.cursor[i] = int8_t(s - 1);
    } else {
      reject(proposals, rays, i, kRejectNoMutation);
    }
  }
}

}  // namespace erpt
