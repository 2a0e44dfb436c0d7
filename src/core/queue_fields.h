// The only place queue fields are declared: one X-macro per queue, one line per field. Three
// kinds of field, each expanding to one column per component (Embree's streams read columns):
//   F(type, name, default, doc)  a scalar column `name`;
//   V(name, doc)                 a Vec3: columns nameX, nameY, nameZ;
//   C(name, doc)                 a Color: columns nameR, nameG, nameB.
// soa.h turns a list into a struct with the columns, a Row type with one member per field
// (the default is the Row's), row(i) / setRow(i, row), and nameAt(i) / nameSet(i, value) for
// the vector and colour fields.
#pragma once

// Rays as Embree's stream API reads them (RTCRayNp): one column per component.
#define ERPT_RAY_FIELDS(F, V, C)                                                                    \
  V(org, "origin")                                                                                  \
  F(float, tnear, {}, "start of the valid interval")                                                \
  V(dir, "direction (need not be normalized)")                                                      \
  F(float, time, {}, "motion blur time (unused, 0)")                                                \
  F(float, tfar, {}, "end of the interval; the hit distance after intersect, -inf if occluded")     \
  F(unsigned, mask, {}, "Embree ray mask")                                                          \
  F(unsigned, id, {}, "Embree ray id")                                                              \
  F(unsigned, flags, {}, "Embree ray flags")

// Closest-hit results (RTCHitNp).
#define ERPT_HIT_FIELDS(F, V, C)                                                                    \
  V(ng, "Embree's unnormalized geometric normal")                                                   \
  F(float, u, {}, "triangle: barycentric of vertex 1; sphere: u")                                   \
  F(float, v, {}, "triangle: barycentric of vertex 2; sphere: v")                                   \
  F(unsigned, primID, {}, "primitive id (scene.h: triangles, then spheres)")                        \
  F(unsigned, geomID, {}, "RTC_INVALID_GEOMETRY_ID on a miss")                                      \
  F(unsigned, instID, {}, "Embree instance geometry of the hit (tracer-internal)")

// A camera sample of the direct-lighting integrator, as it moves through its stages.
#define ERPT_DIRECT_SAMPLE_FIELDS(F, V, C)                                                          \
  F(uint32_t, pixel, {}, "pixel index y * width + x")                                               \
  F(uint32_t, sample, {}, "sample index within the pixel")                                          \
  C(radiance, "radiance gathered so far")                                                           \
  C(shadow, "next-event contribution if the shadow ray is unoccluded")                              \
  C(bsdf, "BSDF sample weight f*cos/pdf (0: no BSDF ray)")                                          \
  F(float, bsdfPdf, {}, "solid-angle pdf of the BSDF sample (0 for a Dirac lobe)")                  \
  V(hit, "first-hit position, for the light pdf of BSDF-sampled emitter hits")

// A path of the wavefront path tracer, indexed by its id within the batch (it does not
// move: compaction moves the slots that point at it).
#define ERPT_PATH_FIELDS(F, V, C)                                                                   \
  F(uint32_t, pixel, {}, "pixel index y * width + x")                                               \
  F(uint32_t, sample, {}, "sample index within the pixel")                                          \
  F(uint32_t, runIndex, {}, "index of the sample within its path-tracer run (PathSampleSet)")         \
  F(uint32_t, depth, {}, "segments traced so far (the camera ray is segment 1)")                    \
  C(throughput, "product of BSDF weights (f cos / pdf) / RR survival")                              \
  C(radiance, "radiance gathered so far")                                                           \
  F(float, prevPdf, {}, "solid-angle pdf of the last BSDF sample; 0 after a Dirac lobe or at the camera") \
  V(prev, "position of the vertex the current ray left (for emitter-hit MIS)")                      \
  F(float, filmX, {}, "film position of the camera ray, x in pixels")                               \
  F(float, filmY, {}, "film position, y in pixels")                                                 \
  F(float, pLength, {}, "product of Russian-roulette survival probabilities so far (ERPT's p_length)") \
  F(float, etaSquared, {}, "product of the squared relative IORs crossed so far (Russian roulette's boost)") \
  F(int32_t, lastVertex, {}, "seed recording: index of the path's newest vertex in the vertex history")

// One live path's place in the ray streams: slot k of the ray, hit and shadow-ray queues
// belongs to path `path`. Compaction moves slots; the path state stays where it is.
#define ERPT_PATH_SLOT_FIELDS(F, V, C)                                                              \
  F(uint32_t, path, {}, "path id (index into PathQueue)")                                           \
  F(uint8_t, alive, {}, "1 while the path continues after this bounce")                             \
  C(nee, "next-event contribution, added if the shadow ray is unoccluded")                          \
  /* Seed recording only: what the contributions of this bounce were made of. */                    \
  F(float, pLengthHere, {}, "p_length of the paths ending at this hit (before this bounce's roulette)") \
  F(float, emitWeight, {}, "MIS weight of emission found at this hit (0: none)")                    \
  C(emit, "unweighted estimate of that emission (throughput * Le)")                                 \
  F(float, neeWeight, {}, "MIS weight of the next-event connection (0: none)")                      \
  F(float, neeBsdfPdf, {}, "BSDF pdf of the connection direction")                                  \
  F(float, neeLightPdf, {}, "area-measure density of the light point (p_light * p_area)")           \
  F(uint8_t, neeLightKind, {}, "VertexKind of the light vertex")                                    \
  F(int32_t, neeLightEmitter, {}, "index of the light in Scene::emitters")                          \
  V(neeLight, "light point (environment: a point far along the direction)")                         \
  V(neeLightN, "light surface normal")

// A path vertex as ERPT's chains see it (the PathVertex view, erpt_path.h).
#define ERPT_PATH_VERTEX_FIELDS(F, V, C)                                                            \
  V(p, "position")                                                                                  \
  V(ns, "shading normal")                                                                           \
  F(float, tangentAngle, 0, "anisotropic BSDFs: their frame's s, as an angle about ns from Frame(ns).s") \
  V(ng, "geometric normal (unit, from the triangle winding)")                                       \
  F(int32_t, material, -1, "material index (-1 for eye and environment vertices)")                  \
  F(float, u, {}, "texture coordinate u")                                                           \
  F(float, v, {}, "texture coordinate v")                                                           \
  F(uint8_t, kind, 0, "VertexKind (kEyeVertex = 0)")                                                \
  F(int32_t, emitter, -1, "light and environment vertices: index into Scene::emitters (-1 otherwise)")

// A path vertex, both in the path tracer's per-batch vertex history (where `parent` links a
// vertex to the one before it on the same path) and in the seed store (where a seed's
// vertices are consecutive, eye first): the path vertex plus how it was sampled.
#define ERPT_VERTEX_FIELDS(F, V, C)                                                                 \
  ERPT_PATH_VERTEX_FIELDS(F, V, C)                                                                  \
  F(float, pdfForward, {}, "p_d of the direction sampled from here to the next vertex (solid angle); for a specular vertex the probability p_s of the lobe taken") \
  F(int32_t, parent, -1, "previous vertex of the same path, -1 at the eye")

// One seed for ERPT: a complete path (one contributing light connection) and how the path
// tracer sampled it. X_f (what the path tracer added to the image) = misWeight * estimate.
#define ERPT_SEED_FIELDS(F, V, C)                                                                   \
  F(uint32_t, pixel, {}, "pixel index y * width + x")                                               \
  F(uint32_t, path, {}, "index of the path (sample) that made it within its path-tracer run")       \
  F(float, filmX, {}, "film position x in pixels")                                                  \
  F(float, filmY, {}, "film position y in pixels")                                                  \
  F(uint8_t, explicitLight, {}, "1: reached the light by next-event estimation; 0: a BSDF sample hit it") \
  F(float, misWeight, {}, "MIS weight of this technique for this path")                             \
  C(estimate, "unweighted estimate f / p of the path")                                              \
  F(float, pLength, {}, "product of Russian-roulette survival probabilities (p_length)")            \
  F(float, pLight, {}, "explicit: area density of the light point (p_light * p_area); implicit: what NEE would have used") \
  F(uint32_t, vertexBegin, {}, "first vertex in the seed store's vertex queue")                     \
  F(uint32_t, vertexCount, {}, "vertices, eye and light included")

// One Markov chain of ERPT (equal deposition, paper figure 6). Its current path's vertices
// live in a VertexQueue at rows [slot * kMaxChainVertices, + vertexCount).
#define ERPT_CHAIN_FIELDS(F, V, C)                                                                  \
  F(uint64_t, key, {}, "random stream of the chain (seed, chain number)")                           \
  F(uint32_t, step, {}, "steps taken so far (the random dimension base)")                           \
  F(uint32_t, stepsLeft, {}, "steps still to run; 0: the slot is free")                             \
  F(uint8_t, vertexCount, {}, "vertices of the current path, eye and light included")               \
  F(uint64_t, signature, {}, "vertex kinds of the current path, 4 bits each (erpt_path.h)")         \
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
  F(float, largeWeight, {}, "large step: W(z) = lum(f) / q of the proposed path")

// What one chain step deposits: kDepositsPerStep rows per chain slot (the paper's rule fills
// one, expected values two). Applied to the film in slot order, so the image does not depend
// on the thread count.
#define ERPT_DEPOSIT_FIELDS(F, V, C)                                                                \
  F(float, x, {}, "film position of the deposit, x")                                                \
  F(float, y, {}, "y")                                                                              \
  C(energy, "energy deposited there (black: no deposit)")
