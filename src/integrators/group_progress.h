// The progress of a chain integrator's group of sample passes (ERPT): the share of the chain
// steps the group is expected to take, where the time goes (the seeds of a small image come in
// one batch, whose chains then run before the next share of seeds is known). It is reported as
// it grows, never going back, from whichever thread moved it (one at a time). The share of the
// group's seeds traced is kept for a stop (the samples whose seeds the chains took).
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <mutex>

namespace erpt {

class GroupProgress {
 public:
  // A new group: `report` gets its fraction done; the machine had taken `stepsBefore` steps.
  void start(std::function<void(double)> report, uint64_t stepsBefore, double expectedSteps) {
    std::lock_guard<std::mutex> lock(mutex_);
    report_ = std::move(report);
    stepsBase_ = stepsBefore;
    steps_ = stepsBefore;
    expectedSteps_ = std::max(1.0, expectedSteps);
    seeds_ = 0;
    reported_ = 0;
  }
  // The share of the group's samples whose seeds went to the chains so far.
  void seeds(double share) {
    std::lock_guard<std::mutex> lock(mutex_);
    seeds_ = share;
    update();
  }
  // The chain machine's steps so far (ChainLanes::Config::onSteps).
  void chainSteps(uint64_t steps) {
    std::lock_guard<std::mutex> lock(mutex_);
    steps_ = std::max(steps_, steps);
    update();
  }
  double seedShare() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return seeds_;
  }

 private:
  void update() {
    // Below 1 until the group's last seeds are in: the expected steps are an estimate.
    const double f = std::min(double(steps_ - stepsBase_) / expectedSteps_, seeds_ < 1 ? 0.99 : 1.0);
    if (f <= reported_ || !report_) return;
    reported_ = f;
    report_(f);
  }
  mutable std::mutex mutex_;
  std::function<void(double)> report_;
  uint64_t stepsBase_ = 0, steps_ = 0;
  double expectedSteps_ = 1, seeds_ = 0, reported_ = 0;
};

}  // namespace erpt
