// The factors a path contribution is made of, shared by the mutations' measures: BSDF values
// at non-specular and specular vertices, emission, the area-to-solid-angle factor, and the
// fixed tail a mutation leaves untouched (docs/erpt-acceptance.md).
#pragma once

#include "kernels/erpt_path.h"

namespace erpt::factors {

// f(wi, wo) |cos(wo)| of a non-specular vertex (wi towards the camera side, world space).
Color evalAt(const MeasureContext& c, const PathVertex& v, Vec3 wi, Vec3 wo);
// Value of the Dirac lobe taking wi to wo at a specular vertex (radiance transport); black
// off the lobe. `adjoint`: the importance-transport value instead.
Color specularAt(const MeasureContext& c, const PathVertex& v, Vec3 wi, Vec3 wo, bool adjoint);
// The solid-angle density with which BSDF sampling at non-specular vertex v picks wo (the lobe
// choice included), as the path tracer samples it.
float pdfAt(const MeasureContext& c, const PathVertex& v, Vec3 wi, Vec3 wo);
// At a specular vertex: the Dirac lobe's value (radiance transport) and the probability that
// BSDF sampling picks that lobe; false off every lobe.
bool specularLobeAt(const MeasureContext& c, const PathVertex& v, Vec3 wi, Vec3 wo, Color& value, float& probability);
// BSDF sampling at surface vertex v with wi the direction the walk arrived from (towards the
// camera side for the eye's walk, the light side for the light's): the sampled direction wo,
// and v.kind set to the lobe taken (specular for a Dirac lobe). False when the sample failed
// or carries nothing. pdfAt / specularLobeAt give its density.
bool sampleAt(const MeasureContext& c, PathVertex& v, Vec3 wi, float u1, float u2, float u3, Vec3& wo);
// The relative IOR crossed from wi to wo at v (bsdfEta): what the path tracer's roulette saw.
float etaAt(const MeasureContext& c, const PathVertex& v, Vec3 wi, Vec3 wo);
// Radiance (area light, environment) or intensity (point light) a light vertex sends along w.
Color emittedAlong(const MeasureContext& c, const PathVertex& light, Vec3 w);
bool isPointLight(const MeasureContext& c, const PathVertex& v);
// Solid angle at `from` per unit area at `to`: |cos_g(to)| / d^2 (point light 1 / d^2,
// environment 1). Rule 3's geometry term without the cosine at `from` (the BSDF carries it).
float areaFactor(const MeasureContext& c, const PathVertex& from, const PathVertex& to);
// The factor of vertices [first, n) in area measure (a tail vertex stands for itself and all
// after it).
Color fixedTail(const MeasureContext& c, const PathVertex* path, int n, int first);
// The same, from the cache when it holds it, else computed (and cached when `cache` is given).
Color tailFrom(const MeasureContext& c, const PathVertex* path, int n, int first, FixedTail* cache);

}  // namespace erpt::factors
