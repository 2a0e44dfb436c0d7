#include "stop_signals.h"

#include <unistd.h>

#include <csignal>
#include <cstring>

#include "erpt/image_io.h"

namespace erpt::cli {

namespace {
std::atomic<bool> stopRequested{false};
std::atomic<bool> stopEnabled{false};
std::atomic<int> stopSignal{0};
static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<int>::is_always_lock_free,
              "signal handlers may only touch lock-free atomics");

void say(const char* text) {
  const ssize_t ignored = write(STDERR_FILENO, text, std::strlen(text));
  (void)ignored;
}

// Only async-signal-safe calls here: atomics, write, unlink, _exit.
void onSignal(int sig) {
  if (stopEnabled.load() && !stopRequested.exchange(true)) {
    stopSignal.store(sig);
    say("\nerpt: stopping after the current batch and writing the passes completed (again to quit at once)\n");
    return;
  }
  removePendingImageFiles();
  _exit(128 + sig);
}
}  // namespace

void installSignalHandlers() {
  struct sigaction action;
  std::memset(&action, 0, sizeof action);
  action.sa_handler = onSignal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

StopOnSignal::StopOnSignal() { stopEnabled.store(true); }
StopOnSignal::~StopOnSignal() { stopEnabled.store(false); }
const std::atomic<bool>* StopOnSignal::flag() const { return &stopRequested; }
int StopOnSignal::signal() const { return stopSignal.load(); }

}  // namespace erpt::cli
