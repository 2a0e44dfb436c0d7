// The Mitsuba plugin name of a material's or emitter's kind ("roughconductor", "spot"), as
// `erpt info` and the Python module's Scene.info() show them.
#pragma once

#include "erpt/material.h"
#include "erpt/scene.h"

namespace erpt {

const char* bsdfKindName(BsdfKind kind);
const char* emitterKindName(const Emitter& emitter);

}  // namespace erpt
