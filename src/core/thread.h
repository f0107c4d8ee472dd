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

/// A thread that names itself `name` (a string that outlives its start, such as a literal) and
/// then runs `f`.
template <class F>
std::thread start_named_thread(const char* name, F&& f) {
  return std::thread([name, f = std::forward<F>(f)]() mutable {
    name_this_thread(name);
    f();
  });
}

}  // namespace rescuesim
