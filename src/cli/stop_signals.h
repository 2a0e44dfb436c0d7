// SIGINT / SIGTERM in the CLI. Outside a render that can stop early, a signal ends the process
// at once (removing any image half-written). During one (StopOnSignal), the first signal asks
// the render to stop at its next batch and write what it completed; a second one ends the
// process at once, writing nothing.
#pragma once

#include <atomic>

namespace erpt::cli {

void installSignalHandlers();

class StopOnSignal {
 public:
  StopOnSignal();
  ~StopOnSignal();
  const std::atomic<bool>* flag() const;
  // The signal that asked to stop (0: none) and the exit status for it (128 + signal).
  int signal() const;
  int exitStatus() const { return 128 + signal(); }
};

}  // namespace erpt::cli
