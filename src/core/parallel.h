// Thread pool control and the one loop every stage uses: forEachRange() splits [0, n) into
// ranges across the pool's threads and records the stage's time under its name. Every parallel
// loop of the renderer goes through here, so the ThreadSanitizer build can swap the backend
// (TBB normally; plain std::threads with ERPT_STD_THREADS, see parallel.cpp).
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/soa.h"
#include "erpt/stage_times.h"

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

void forEachRange(const char* stage, size_t n, size_t grain, const std::function<void(IndexRange)>& fn,
                  StageTimes* times = nullptr);

// Which of the pool's threads runs the calling task: a number below workerSlots(), never the
// same for two tasks running at once.
size_t workerIndex();
size_t workerSlots();

// Scratch that each thread keeps across the tasks it runs (a wavefront's queues): made on a
// thread's first local() and kept until the object dies. Only the calling task may use it.
template <class T>
class PerThread {
 public:
  PerThread() : slots_(workerSlots()) {}
  T& local() {
    std::unique_ptr<T>& slot = slots_.at(workerIndex());
    if (!slot) slot = std::make_unique<T>();
    return *slot;
  }

 private:
  std::vector<std::unique_ptr<T>> slots_;
};

}  // namespace erpt
