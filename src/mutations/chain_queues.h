// The chain engine's queues, declared once as queue_fields.h declares the others (F scalar,
// V Vec3, C Color columns; soa.h builds the structs): the chains, their proposals and the
// deposits of one step. Chain slot i owns row i of each.
#pragma once

#include "core/queues.h"
#include "core/soa.h"

// One Markov chain of ERPT (equal deposition, paper figure 6). Its current path's vertices
// live in a VertexQueue at rows [slot * kMaxChainVertices, + vertexCount).
#define ERPT_CHAIN_FIELDS(F, V, C)                                                                  \
  F(uint64_t, key, {}, "random stream of the chain (seed, chain number)")                           \
  F(uint32_t, step, {}, "steps taken so far (the random dimension base)")                           \
  F(uint32_t, stepsLeft, {}, "steps still to run; 0: the slot is free")                             \
  F(uint8_t, vertexCount, {}, "vertices of the current path, eye and light included")               \
  F(uint64_t, signature, {}, "vertex kinds of the current path, 3 bits each (erpt_path.h)")         \
  F(float, fLum, {}, "lum(f) of the current path in the measure of mutation fKind (a cache)")       \
  F(uint8_t, fKind, {}, "MutationKind whose measure fLum is in (Mutation::measure); None: not known") \
  C(tail, "fixed tail of f for mutation tailKind (erpt_path.h)")                                    \
  F(uint8_t, tailKind, {}, "MutationKind whose measure the tail is in (Mutation::measure); None: not known") \
  F(float, filmX, {}, "film position of the current path, x in pixels")                             \
  F(float, filmY, {}, "y")                                                                          \
  C(color, "rgb(f) / lum(f) of the current path")                                                   \
  F(float, energy, {}, "luminance each step deposits (e_d; detailed balance: e / m)")               \
  F(uint32_t, runPixel, {}, "consecutive-sample filter: pixel of the chain's last deposits")        \
  F(uint32_t, runLength, {}, "how many steps in a row the chain has been on runPixel")              \
  F(float, largeWeight, {}, "MLT: W = lum(f) / q of the current path for the large step (large_step.h); < 0: not known")

// The proposal of one chain for the current step (same slot as the chain). Regenerated
// vertices are written to the proposal's VertexQueue rows of that slot; the others are the
// chain's.
#define ERPT_PROPOSAL_FIELDS(F, V, C)                                                               \
  F(uint8_t, mutation, {}, "MutationKind chosen for this step")                                     \
  F(float, perturbSize, {}, "perturbation size of this proposal: lens square half-side or disk radius, caustic angle range, in pixels") \
  F(uint8_t, state, {}, "ProposalState: walking, connecting, complete or rejected")                 \
  F(uint8_t, reason, {}, "RejectReason when rejected")                                              \
  F(int8_t, cursor, {}, "index of the vertex the ray in flight will produce")                       \
  F(int8_t, walk, {}, "+1: the walk goes from the eye towards the light; -1: towards the eye")      \
  F(int8_t, regenFirst, {}, "first vertex the proposal regenerates (the mutation's start writes it)") \
  F(int8_t, regenLast, {}, "last vertex the proposal regenerates")                                  \
  F(int8_t, connectTo, {}, "fixed vertex the last regenerated one connects to (0: the eye), -1: none") \
  F(float, filmX, {}, "film position of the proposed path, x")                                      \
  F(float, filmY, {}, "y")                                                                          \
  F(float, acceptance, {}, "q(y -> z); 0 when rejected")                                            \
  F(uint8_t, component, {}, "mixture component (PMC-ER: index of the radius) the proposal was made with; 0 for ERPT") \
  F(float, selection, {}, "a(z) / a(y): probability of choosing this proposal's mutation and size at z over at y (1 unless the choice depends on the film position)") \
  C(color, "rgb(f) / lum(f) of the proposed path")                                                  \
  F(uint8_t, vertexCount, {}, "large step: vertices of the proposed path (perturbations keep the chain's)") \
  F(uint64_t, signature, {}, "large step: vertex kinds of the proposed path")                       \
  F(float, largeWeight, {}, "large step: W(z) = lum(f) / q of the proposed path")            \
  F(float, ratio, {}, "bidirectional mutation: f(z) T(z -> y) / (f(y) T(y -> z)) on luminance") \
  F(float, measureRatio, {}, "the factor of f(z) / f(y) in the unit's measure that the vertices alone do not give (manifold: the chains' |d omega / dA| at z over y, measured by its stage); 1 otherwise")

// What one chain step deposits: kDepositsPerStep rows per chain slot (the paper's rule fills
// one, expected values two). Applied to the film in slot order, so the image does not depend
// on the thread count.
#define ERPT_DEPOSIT_FIELDS(F, V, C)                                                                \
  F(float, x, {}, "film position of the deposit, x")                                                \
  F(float, y, {}, "y")                                                                              \
  C(energy, "energy deposited there (black: no deposit)")

namespace erpt {

ERPT_SOA_STRUCT(ChainQueue, ERPT_CHAIN_FIELDS)
ERPT_SOA_STRUCT(ProposalQueue, ERPT_PROPOSAL_FIELDS)
ERPT_SOA_STRUCT(DepositQueue, ERPT_DEPOSIT_FIELDS)

}  // namespace erpt
