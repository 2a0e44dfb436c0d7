#pragma once

#include "erpt/integrators.h"

namespace erpt {

// `--integrator pssmlt`: primary-sample-space MLT over the path tracer or BDPT (docs/pssmlt.md).
IntegratorModule pssmltModule();

}  // namespace erpt
