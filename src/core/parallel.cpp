#include "core/parallel.h"

#include <xmmintrin.h>
#include <pmmintrin.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <thread>

#ifdef ERPT_STD_THREADS
#include <vector>
#else
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <tbb/task_scheduler_observer.h>
#endif

namespace erpt {

namespace {
void setFlushToZero() {
  _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
  _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
}

void addStageTime(StageTimes* times, const char* stage, std::chrono::steady_clock::time_point start) {
  if (times) times->add(stage, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}
}  // namespace

#ifdef ERPT_STD_THREADS
// The ThreadSanitizer build. Debian's libtbb is not instrumented, so TSan cannot see the
// synchronisation by which TBB hands a loop's data to its workers and back, and reports every
// such hand-off as a race. Here each loop starts its threads and joins them (which TSan
// understands), and the workers take fixed-size ranges from a shared counter. The guarantees
// the renderer may rely on are the same as under TBB: the ranges of one loop run in any order
// on any threads, and everything written before the loop is seen by its ranges, everything
// they write is seen after it.
namespace {
// Per calling thread, as a render's pool belongs to the thread that made it (tests run split
// renders on several threads of one process at once).
thread_local int poolThreads = 1;
thread_local size_t currentWorker = 0;
thread_local bool insideLoop = false;
}  // namespace

struct ThreadPool::Impl {
  int previousThreads;
};

ThreadPool::ThreadPool(int threads) {
  threads_ = threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency()));
  setFlushToZero();
  impl_ = std::make_unique<Impl>(Impl{poolThreads});
  poolThreads = threads_;
}

ThreadPool::~ThreadPool() { poolThreads = impl_->previousThreads; }

size_t workerIndex() { return currentWorker; }
size_t workerSlots() { return size_t(std::max(1, poolThreads)); }

void forEachRange(const char* stage, size_t n, size_t grain, const std::function<void(IndexRange)>& fn,
                  StageTimes* times) {
  const auto start = std::chrono::steady_clock::now();
  grain = std::max<size_t>(1, grain);
  const size_t ranges = (n + grain - 1) / grain;
  std::atomic<size_t> next{0};
  auto work = [&] {
    for (size_t r; (r = next.fetch_add(1)) < ranges;) fn(IndexRange{r * grain, std::min(n, (r + 1) * grain)});
  };
  const size_t workers = std::min<size_t>(workerSlots(), ranges);
  if (insideLoop || workers <= 1) {  // a nested loop runs on the thread that asked for it
    work();
  } else {
    std::vector<std::thread> threads;
    for (size_t w = 1; w < workers; ++w)
      threads.emplace_back([&, w] {
        setFlushToZero();
        currentWorker = w, insideLoop = true;
        work();
      });
    insideLoop = true;
    work();
    insideLoop = false;
    for (std::thread& t : threads) t.join();
  }
  addStageTime(times, stage, start);
}
#else
namespace {
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

// The arena's slot of the calling thread; the arena has max_concurrency() slots whatever the
// global_control limit (which only caps how many are busy).
size_t workerIndex() { return size_t(std::max(0, tbb::this_task_arena::current_thread_index())); }
size_t workerSlots() { return size_t(std::max(1, tbb::this_task_arena::max_concurrency())); }

void forEachRange(const char* stage, size_t n, size_t grain, const std::function<void(IndexRange)>& fn,
                  StageTimes* times) {
  const auto start = std::chrono::steady_clock::now();
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, std::max<size_t>(1, grain)),
                    [&](const tbb::blocked_range<size_t>& r) { fn(IndexRange{r.begin(), r.end()}); });
  addStageTime(times, stage, start);
}
#endif

}  // namespace erpt
