#include "erpt/parallel.h"

#include <xmmintrin.h>
#include <pmmintrin.h>

#include <chrono>
#include <thread>

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_scheduler_observer.h>

namespace erpt {

namespace {
void setFlushToZero() {
  _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
  _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
}

class FlushToZeroObserver : public tbb::task_scheduler_observer {
 public:
  FlushToZeroObserver() { observe(true); }
  ~FlushToZeroObserver() override { observe(false); }
  void on_scheduler_entry(bool) override { setFlushToZero(); }
};
}  // namespace

struct ThreadPool::Impl {
  tbb::global_control control;
  FlushToZeroObserver observer;
  explicit Impl(int n) : control(tbb::global_control::max_allowed_parallelism, size_t(n)) {}
};

ThreadPool::ThreadPool(int threads) {
  threads_ = threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
  setFlushToZero();  // the calling thread also runs tasks
  impl_ = std::make_unique<Impl>(threads_);
}

ThreadPool::~ThreadPool() = default;

void forEachRange(const char* stage, size_t n, size_t grain, const std::function<void(IndexRange)>& fn,
                  StageTimes* times) {
  auto start = std::chrono::steady_clock::now();
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, std::max<size_t>(1, grain)),
                    [&](const tbb::blocked_range<size_t>& r) { fn(IndexRange{r.begin(), r.end()}); });
  if (times)
    times->add(stage, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

}  // namespace erpt
