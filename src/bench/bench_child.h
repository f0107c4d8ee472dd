#pragma once
// Bench measurements in a forked child process: each runs in a fresh process, so its peak memory
// and CPU time are its own and nothing it set up (GL contexts, roscpp, DDS) outlives it.

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <exception>
#include <string>
#include <nlohmann/json.hpp>

namespace rescuesim::bench {

/// What a child reported, and the resources it used.
struct ChildReport {
  nlohmann::ordered_json report;  ///< `work`'s result, or {"error": why}
  struct rusage usage {};
};

/// Runs `work` (returning JSON) in a forked child; its exceptions become {"error": what}.
template <class Work>
ChildReport run_in_child(Work&& work) {
  using json = nlohmann::ordered_json;
  ChildReport result;
  int fds[2];
  if (::pipe(fds) != 0) {
    result.report = json{{"error", "pipe failed"}};
    return result;
  }
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(fds[0]);
    json out;
    try {
      out = work();
    } catch (const std::exception& e) {
      out = {{"error", e.what()}};
    }
    const std::string text = out.dump();
    (void)!::write(fds[1], text.data(), text.size());
    ::_exit(0);
  }
  ::close(fds[1]);
  std::string text;
  char buf[65536];
  ssize_t n;
  while ((n = ::read(fds[0], buf, sizeof buf)) > 0) text.append(buf, static_cast<std::size_t>(n));
  ::close(fds[0]);
  int status = 0;
  ::wait4(pid, &status, 0, &result.usage);
  result.report = text.empty() ? json{{"error", "child process died"}} : json::parse(text);
  return result;
}

}  // namespace rescuesim::bench
