// Internal to src/models: Mitsuba 0.6's `coating` and `roughcoating`, which bsdf.cpp's entry
// points hand their materials to (the conventions of bsdf.h: local frame, wi towards the
// camera, eval = f |cos(wo)| without Dirac lobes).
#pragma once

#include "models/bsdf.h"

namespace erpt {

Color coatingEval(const Material& m, const SurfaceColors& c, Vec3 wi, Vec3 wo);
float coatingPdf(const Material& m, const SurfaceColors& c, Vec3 wi, Vec3 wo);
bool coatingSample(const Material& m, const SurfaceColors& c, Vec3 wi, float u1, float u2, float u3, BsdfSample& s);
// The Dirac lobe along the mirror direction wo (bsdfDeltaLobe's contract; the caller has
// checked that wo is the mirror direction): the smooth coat's reflection plus the coated
// BSDF's own mirror lobe seen through the layer.
bool coatingDeltaLobe(const Material& m, const SurfaceColors& c, Vec3 wi, Vec3 wo, Color& value, float& probability);

// Defined in bsdf.cpp: the share of light crossing a (rough)plastic's or roughcoating's coat
// at incidence cos(theta): 1 - Fresnel when smooth, 1 - the rough lobe's tabulated albedo.
float coatTransmittance(const Material& m, float cosTheta);

}  // namespace erpt
