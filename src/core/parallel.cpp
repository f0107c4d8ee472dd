#include "core/parallel.h"

#include "core/thread.h"
#include "core/tsan.h"

#include <atomic>
#include <memory>
#include <mutex>

// ThreadSanitizer cannot see how Debian's (uninstrumented) TBB hands a task's writes back to the
// caller, so under TSan the pool is std::threads with a mutex and condition variables it does
// see (PlainPool below); every other build uses TBB's.
#if defined(RESCUESIM_UNDER_TSAN)
#define RESCUESIM_PLAIN_POOL 1
#endif

#if defined(RESCUESIM_PLAIN_POOL)
#include <algorithm>
#include <condition_variable>
#include <exception>
#include <thread>
#include <vector>

#include <unistd.h>
#else
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#endif

namespace rescuesim {

namespace {
std::mutex g_mutex;
std::atomic<int> g_threads{0};
}  // namespace

#if defined(RESCUESIM_PLAIN_POOL)

namespace {

/// One parallel_for call: indices are claimed one at a time under the pool's mutex, so each
/// task's writes reach the caller through that mutex (as TSan sees it).
struct Job {
  const std::function<void(std::size_t)>* task = nullptr;
  std::size_t n = 0;
  std::size_t next = 0;      ///< first index not yet claimed
  std::size_t running = 0;   ///< claimed and not yet returned
  std::exception_ptr error;  ///< the first exception a task threw
};

/// A fixed set of worker threads and the jobs with indices still to claim. A caller works on
/// its own job only, so a nested parallel_for inside a task always finishes (its caller can run
/// every index itself) and a waiting caller never runs its own caller's tasks.
class PlainPool {
 public:
  explicit PlainPool(int workers) {
    for (int i = 0; i < workers; ++i) threads_.push_back(start_named_thread("pool", [this] { work(); }));
  }
  ~PlainPool() {
    // in a child forked after the pool started (batch trials) its threads do not exist and a
    // worker may have held mutex_ at the fork: leave them be, as the child leaves without them
    if (::getpid() != owner_) {
      for (std::thread& t : threads_) t.detach();
      return;
    }
    {
      std::lock_guard lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    for (std::thread& t : threads_) t.join();
  }
  PlainPool(const PlainPool&) = delete;
  PlainPool& operator=(const PlainPool&) = delete;

  void run(Job& job) {
    std::unique_lock lock(mutex_);
    jobs_.push_back(&job);
    wake_.notify_all();
    while (run_one(job, lock)) {
    }
    done_.wait(lock, [&] { return job.running == 0; });
    if (job.error) std::rethrow_exception(job.error);
  }

 private:
  /// Claims and runs one index of `job` (the lock is released while the task runs); false when
  /// every index is already claimed. Called and returns with `lock` held.
  bool run_one(Job& job, std::unique_lock<std::mutex>& lock) {
    if (job.next >= job.n) return false;
    const std::size_t i = job.next++;
    ++job.running;
    if (job.next == job.n) std::erase(jobs_, &job);
    lock.unlock();
    std::exception_ptr error;
    try {
      (*job.task)(i);
    } catch (...) {
      error = std::current_exception();
    }
    lock.lock();
    if (error) {
      if (!job.error) job.error = error;
      if (job.next < job.n) std::erase(jobs_, &job);
      job.next = job.n;  // the remaining indices are not run, as TBB cancels them
    }
    // after this the job may be gone (its caller returns once running is 0 under the lock)
    if (--job.running == 0 && job.next >= job.n) done_.notify_all();
    return true;
  }

  void work() {
    std::unique_lock lock(mutex_);
    for (;;) {
      wake_.wait(lock, [&] { return stop_ || !jobs_.empty(); });
      if (stop_) return;
      run_one(*jobs_.front(), lock);
    }
  }

  std::mutex mutex_;
  std::condition_variable wake_;  ///< a job was queued, or the pool stops
  std::condition_variable done_;  ///< some job's last task returned
  std::vector<Job*> jobs_;        ///< jobs with indices not yet claimed, oldest first
  bool stop_ = false;
  const pid_t owner_ = ::getpid();  ///< the process whose threads these are
  std::vector<std::thread> threads_;
};

/// The pool of the current limit. shared_ptr because set_worker_threads may replace it while a
/// parallel_for still runs on the old one, which then lives until that call returns.
std::shared_ptr<PlainPool> g_pool;

std::shared_ptr<PlainPool> current_pool() {
  std::lock_guard lock(g_mutex);
  if (!g_pool) {
    const int limit = g_threads.load(std::memory_order_relaxed);
    const int threads = limit > 0 ? limit : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    g_pool = std::make_shared<PlainPool>(threads - 1);  // the caller is the last thread
  }
  return g_pool;
}

}  // namespace

void set_worker_threads(int n) {
  std::shared_ptr<PlainPool> old;
  {
    std::lock_guard lock(g_mutex);
    old = std::move(g_pool);  // the next parallel_for makes a pool of the new size
    g_threads.store(n > 0 ? n : 0, std::memory_order_relaxed);
  }
}

int worker_threads() { return g_threads.load(std::memory_order_relaxed); }

void parallel_for(std::size_t n, const std::function<void(std::size_t)>& task) {
  if (n < 2 || worker_threads() == 1) {
    for (std::size_t i = 0; i < n; ++i) task(i);
    return;
  }
  Job job;
  job.task = &task;
  job.n = n;
  current_pool()->run(job);
}

#else

namespace {
std::unique_ptr<tbb::global_control> g_limit;
}  // namespace

void set_worker_threads(int n) {
  std::lock_guard lock(g_mutex);
  g_limit.reset();
  if (n > 0) g_limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(n));
  g_threads.store(n > 0 ? n : 0, std::memory_order_relaxed);
}

int worker_threads() { return g_threads.load(std::memory_order_relaxed); }

void parallel_for(std::size_t n, const std::function<void(std::size_t)>& task) {
  if (n < 2 || worker_threads() == 1) {
    for (std::size_t i = 0; i < n; ++i) task(i);
    return;
  }
  // one index per TBB task: callers hand over coarse work (a robot's sensors, a physics group)
  tbb::this_task_arena::isolate([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i < r.end(); ++i) task(i);
    });
  });
}

#endif

}  // namespace rescuesim
