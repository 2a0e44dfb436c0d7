// The clock a --time budget's decisions read (RenderSettings::budgetClock): the steady clock,
// or a test's counting clock, which makes the number of passes or rounds a budget takes, and
// so the image, the same on every machine and in every build.
#pragma once

#include <chrono>

#include "erpt/render.h"

namespace erpt {

// Seconds since an arbitrary origin.
inline double budgetSeconds(const RenderSettings& s) {
  if (s.budgetClock) return s.budgetClock();
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace erpt
