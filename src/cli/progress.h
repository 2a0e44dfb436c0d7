// Progress reporting: a redrawn bar with the time left on a terminal, plain lines (every 10%)
// otherwise. The time left extrapolates the time so far over the fraction done.
#pragma once

#include <unistd.h>

#include <chrono>
#include <cstdio>

namespace erpt::cli {

class Progress {
 public:
  explicit Progress(bool enabled)
      : enabled_(enabled), terminal_(isatty(STDERR_FILENO)), start_(std::chrono::steady_clock::now()) {}
  void update(double fraction) {
    if (!enabled_) return;
    const int percent = int(fraction * 100.0 + 1e-9);
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double left = fraction > 1e-3 ? elapsed * (1.0 - fraction) / fraction : -1.0;
    if (terminal_) {
      const int width = 40;
      int filled = int(fraction * width);
      std::fprintf(stderr, "\r[%.*s%*s] %3d%%  %.0f s", filled, "########################################", width - filled, "",
                   percent, elapsed);
      if (left >= 0) std::fprintf(stderr, ", %.0f s left   ", left);
      drawn_ = fraction < 1.0;
      if (!drawn_) std::fprintf(stderr, "\n");
    } else if (percent / 10 > lastDecile_) {
      lastDecile_ = percent / 10;
      std::fprintf(stderr, "progress: %d%% after %.1f s", lastDecile_ * 10, elapsed);
      if (left >= 0 && lastDecile_ < 10) std::fprintf(stderr, ", about %.0f s left", left);
      std::fprintf(stderr, "\n");
    }
    std::fflush(stderr);
  }
  // Ends a bar left unfinished (a stopped render).
  void end() {
    if (drawn_) std::fprintf(stderr, "\n");
    drawn_ = false;
  }

 private:
  bool enabled_, terminal_;
  std::chrono::steady_clock::time_point start_;
  int lastDecile_ = 0;
  bool drawn_ = false;
};

}  // namespace erpt::cli
