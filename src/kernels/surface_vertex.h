// A path vertex at a surface hit, for any row type with the path vertex's fields
// (queue_fields.h's ERPT_PATH_VERTEX_FIELDS: the path tracer's seed history, BDPT's subpaths).
#pragma once

#include "core/queues.h"
#include "models/surface.h"

namespace erpt {

// The vertex's geometry, material and texture coordinates; kind: a Dirac material's or not
// (the walks change it to the lobe they take).
template <class Row>
void setSurfaceVertex(Row& v, const SurfacePoint& sp, const Material& m) {
  v.p = sp.position;
  v.ns = sp.shading.n;
  v.tangentAngle = m.anisotropic() ? sp.shading.tangentAngle() : 0.0f;
  v.ng = sp.geometricNormal;
  v.material = sp.material;
  v.u = sp.u;
  v.v = sp.v;
  v.kind = m.isPureSpecular() ? kSpecularVertex : kNonSpecularVertex;
  v.emitter = sp.emitter;
}

}  // namespace erpt
