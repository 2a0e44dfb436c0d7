// ERPT's view of a path: vertices as plain values, the mutations that apply to a path's
// signature (its sequence of vertex kinds), the perturbation samplers, and the path's
// contribution in the measure each mutation samples in (docs/erpt-acceptance.md derives it).
#pragma once

#include <cstdint>

#include "models/camera.h"
#include "erpt/erpt_settings.h"
#include "models/film_density.h"
#include "models/light_sampler.h"
#include "core/queues.h"

namespace erpt {

// Most vertices a chain holds (eye and light included). A longer path is folded: its vertex
// kMaxChainVertices - 1 becomes a tail vertex carrying the fixed factor of the rest
// (foldPathTail), which no perturbation moves, so chains hold paths of any length.
// 21 vertices: the signature packs each vertex kind into 3 bits of 64, and the longest
// specular chains of the benchmark scenes (light bouncing between a pool's floor and its water
// surface, E S D S D ... L) have up to 19.
constexpr int kMaxChainVertices = 21;

// The tail vertex's fixed factor R: everything from it to the light in area measure, its own
// area factor as seen from the vertex before it included (stored in its shading-normal field,
// which nothing reads at a tail vertex: a vertex field of its own would cost every vertex
// queue 12 bytes for the few folded paths).
// (Color is a Vec3.)
inline Color tailVertexFactor(const PathVertex& v) { return v.ns; }
inline void setTailVertexFactor(PathVertex& v, Color r) {
  v.kind = kTailVertex;
  v.ns = r;
}

// Unit direction from vertex a towards vertex b (an environment vertex b: its direction).
Vec3 directionBetween(const PathVertex& a, const PathVertex& b);
// True when the path reflects at vertex j (its neighbours lie on the same side of it).
bool reflectsAt(const PathVertex* path, int j);

// A path's signature: its vertex kinds, 3 bits per vertex (mutations preserve it).
constexpr int kSignatureBitsPerVertex = 3;
static_assert(kTailVertex < (1 << kSignatureBitsPerVertex), "every VertexKind fits a signature's bits");
static_assert(kMaxChainVertices * kSignatureBitsPerVertex <= 64, "a chain's signature fits 64 bits");
uint64_t packSignature(const uint8_t* kinds, int n);
inline uint8_t kindAt(uint64_t signature, int j) {
  return uint8_t((signature >> (kSignatureBitsPerVertex * j)) & ((1u << kSignatureBitsPerVertex) - 1));
}
// kinds must hold kMaxChainVertices entries.
inline void unpackSignature(uint64_t signature, int n, uint8_t* kinds) {
  for (int j = 0; j < n && j < kMaxChainVertices; ++j) kinds[j] = kindAt(signature, j);
}

// Equal deposition (paper figure 6): a seed of energy e starts floor(u + e / (m e_d)) chains
// of m steps, each step depositing e_d; u uniform in [0, 1) makes the expectation exact. u has
// 53 bits (uniformDouble): with a 24-bit u a seed expecting fewer than 2^-24 chains would
// never start one, and its energy would be lost.
uint32_t chainsForSeed(double energy, double chainLength, double depositEnergy, double u);

// Perturbation angle for caustic perturbations and the direction changes of lens
// perturbations: density proportional to 1/theta on [1e-4, 0.1] rad (Veach and Guibas 1997,
// paper footnote 4), azimuth uniform. Symmetric in solid angle.
Vec3 perturbDirection(Vec3 d, float u1, float u2);
constexpr float kPerturbThetaMin = 1e-4f, kPerturbThetaMax = 0.1f;

struct MeasureContext {
  const Scene& scene;
  const LightSampler& lights;
  const Camera& camera;
  const FilmDensity& film;
};

// The vertices a mutation leaves untouched, with their incoming directions, contribute a
// constant factor to f (the "fixed tail", from tailStart() on). Chains cache it: it cancels in
// the acceptance ratio, but its colour is part of the path's colour.
struct FixedTail {
  Color value{1.0f};
  bool known = false;
};

}  // namespace erpt
