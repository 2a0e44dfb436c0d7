// Progress reporting: a redrawn bar on a terminal, plain lines (every 10%) otherwise.
#pragma once

#include <unistd.h>

#include <cstdio>

namespace erpt::cli {

class Progress {
 public:
  explicit Progress(bool enabled) : enabled_(enabled), terminal_(isatty(STDERR_FILENO)) {}
  void update(double fraction) {
    if (!enabled_) return;
    int percent = int(fraction * 100.0 + 1e-9);
    if (terminal_) {
      const int width = 40;
      int filled = int(fraction * width);
      std::fprintf(stderr, "\r[%.*s%*s] %3d%%", filled, "########################################", width - filled, "",
                   percent);
      if (fraction >= 1.0) std::fprintf(stderr, "\n");
    } else if (percent / 10 > lastDecile_) {
      lastDecile_ = percent / 10;
      std::fprintf(stderr, "progress: %d%%\n", lastDecile_ * 10);
    }
    std::fflush(stderr);
  }

 private:
  bool enabled_, terminal_;
  int lastDecile_ = 0;
};

}  // namespace erpt::cli
