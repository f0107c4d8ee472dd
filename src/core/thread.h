#pragma once
/// Names for the process's own threads: what `top -H`, `perf`, gdb and /proc/PID/task show, so a
/// profile says which bridge or service a thread serves (Linux keeps 15 characters).

#include <thread>
#include <utility>

namespace rescuesim {

/// Names the calling thread; a longer name is cut to 15 characters. Threads it starts later
/// inherit the name unless they set their own (a few of Mesa's helpers started by the render
/// thread show as "render"). Best effort: a failure changes nothing else.
void name_this_thread(const char* name);

namespace detail {
/// Makes, on the calling thread, the process-wide state a new thread may touch first: spdlog's
/// default logger. Debian's libspdlog.so makes it on first use behind a static ThreadSanitizer
/// cannot see through, so a thread whose first log line made or read it unsynchronised shows up
/// as a race on the logger's fields; made before the thread starts, the start orders it.
void before_thread_start();
}  // namespace detail

/// A thread that names itself `name` (a string that outlives its start, such as a literal) and
/// then runs `f`. Every thread of rescuesim's own that may log is started through this.
template <class F>
std::thread start_named_thread(const char* name, F&& f) {
  detail::before_thread_start();
  return std::thread([name, f = std::forward<F>(f)]() mutable {
    name_this_thread(name);
    f();
  });
}

}  // namespace rescuesim
