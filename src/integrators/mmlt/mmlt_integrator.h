#pragma once

#include "erpt/integrators.h"

namespace erpt {

// `--integrator mmlt`: multiplexed MLT over BDPT's strategies (docs/pssmlt.md).
IntegratorModule mmltModule();

}  // namespace erpt
