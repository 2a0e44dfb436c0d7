// The path tracer's and the seed store's queue fields, declared once (the tracer's rays and hits
// are in tracer/ray_queues.h, the chain engine's queues in mutations/chain_queues.h): one
// X-macro per queue, one line per field. Three kinds of field, each expanding to one column per component (Embree's streams read columns):
//   F(type, name, default, doc)  a scalar column `name`;
//   V(name, doc)                 a Vec3: columns nameX, nameY, nameZ;
//   C(name, doc)                 a Color: columns nameR, nameG, nameB.
// soa.h turns a list into a struct with the columns, a Row type with one member per field
// (the default is the Row's), row(i) / setRow(i, row), and nameAt(i) / nameSet(i, value) for
// the vector and colour fields.
#pragma once

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
  F(uint64_t, key, {}, "random stream of the sample, sampleKey(seed, pixel, sample), hashed once at the start") \
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
  F(uint8_t, explicitLight, {}, "the technique: 0 a BSDF sample hit the light, 1 next-event estimation; BDPT's seeds: the strategy's light vertices s") \
  F(float, misWeight, {}, "MIS weight of this technique for this path")                             \
  C(estimate, "unweighted estimate f / p of the path")                                              \
  F(float, pLength, {}, "product of Russian-roulette survival probabilities (p_length)")            \
  F(float, pLight, {}, "explicit: area density of the light point (p_light * p_area); implicit: what NEE would have used") \
  F(uint32_t, vertexBegin, {}, "first vertex in the seed store's vertex queue")                     \
  F(uint32_t, vertexCount, {}, "vertices, eye and light included")

// A vertex of one of BDPT's subpaths (light or camera), in the order the walk made them: the
// path vertex, how much of the path's contribution over its density it carries, and the two
// densities that the MIS weights of every connection through it need (kernels/bdpt_mis.h).
#define ERPT_BDPT_VERTEX_FIELDS(F, V, C)                                                            \
  ERPT_PATH_VERTEX_FIELDS(F, V, C)                                                                  \
  C(beta, "contribution over density of the subpath up to here (bdpt_walk.cpp says what a light vertex's includes)") \
  F(float, pdfForward, {}, "area density of this vertex as its own subpath sampled it (solid angle at infinity)") \
  F(float, pdfReverse, {}, "area density of this vertex sampled from the other side (from the next vertex of its subpath)") \
  F(uint32_t, primitive, {}, "primitive id of a surface or area-light vertex")                       \
  F(int32_t, parent, -1, "previous vertex of the same subpath, -1 at its start")

// A subpath in flight in BDPT's walks (its ray is slot k of the walk's ray queue).
#define ERPT_BDPT_WALK_FIELDS(F, V, C)                                                              \
  F(uint32_t, sample, {}, "the sample (index within the task's chunk) the subpath belongs to")      \
  C(beta, "beta of the vertex the ray will hit, before that vertex's own factors")                   \
  C(scatter, "product of the bounce weights so far (Russian roulette reads it)")                     \
  F(float, etaSquared, {}, "product of the squared relative IORs crossed (Russian roulette's boost)") \
  F(float, pdfNext, {}, "density of the direction just sampled: solid angle, or per unit area across an infinite light's beam") \
  F(int32_t, vertex, {}, "the subpath's newest vertex")                                             \
  F(uint32_t, depth, {}, "segments traced so far")

// One contribution of BDPT (a strategy (s, t) of one sample): its shadow ray is slot k of the
// connection stage's ray queue (disabled for s = 0, which needs none); if unoccluded, `value`
// goes to the sample's radiance or, for light tracing (t = 1), to the film at (filmX, filmY).
#define ERPT_BDPT_CONNECTION_FIELDS(F, V, C)                                                        \
  F(uint32_t, sample, {}, "the sample (index within the task's chunk)")                             \
  C(value, "MIS-weighted contribution")                                                            \
  F(float, misWeight, {}, "its MIS weight")                                                         \
  F(uint16_t, s, {}, "light vertices of the strategy")                                              \
  F(uint16_t, t, {}, "camera vertices of the strategy")                                             \
  F(int32_t, cameraVertex, {}, "the camera end: a subpath vertex (>= 0) or extra vertex -1 - v (a lens point)") \
  F(int32_t, lightVertex, {}, "the light end: a subpath vertex (>= 0), extra vertex -1 - v (a next-event light point) or none (s = 0)") \
  F(uint8_t, toCamera, {}, "1: light tracing (t = 1), splatted at (filmX, filmY)")                  \
  F(float, filmX, {}, "light tracing: the film position, x in pixels")                              \
  F(float, filmY, {}, "light tracing: the film position, y in pixels")
