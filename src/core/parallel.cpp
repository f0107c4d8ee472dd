#include "core/parallel.h"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <memory>
#include <mutex>

namespace rescuesim {

namespace {
std::mutex g_mutex;
std::unique_ptr<tbb::global_control> g_limit;
std::atomic<int> g_threads{0};
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

}  // namespace rescuesim
