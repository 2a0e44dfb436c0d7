// Thread pool control and the one loop every stage uses: forEachRange() splits [0, n) into
// ranges across TBB threads and records the stage's time under its name.
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <string>

#include "erpt/soa.h"

namespace erpt {

// Owns the TBB arena size for a render; also sets flush-to-zero / denormals-are-zero on
// every worker thread (Embree asks for it).
class ThreadPool {
 public:
  explicit ThreadPool(int threads);  // 0 = all hardware threads
  ~ThreadPool();
  int threads() const { return threads_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int threads_;
};

// Seconds spent per stage name (for the render summary and benchmarks).
class StageTimes {
 public:
  void add(const std::string& stage, double seconds) { seconds_[stage] += seconds; }
  const std::map<std::string, double>& all() const { return seconds_; }

 private:
  std::map<std::string, double> seconds_;
};

void forEachRange(const char* stage, size_t n, size_t grain, const std::function<void(IndexRange)>& fn,
                  StageTimes* times = nullptr);

}  // namespace erpt
