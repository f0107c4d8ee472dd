// The batch runner: trials in child processes (or threads), J at a time, each record appended
// to results.jsonl by this process as soon as its trial ends.

#include "batch/batch_runner.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <mutex>
#include <thread>

#include "core/error.h"
#include "core/parallel.h"
#include "core/thread.h"

namespace rescuesim {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

/// Progress bookkeeping shared by both isolation modes.
struct Tally {
  BatchProgress p;
  Clock::time_point t0 = Clock::now();
  Clock::time_point last_report = t0;
  int jobs = 1;

  void update_times() {
    p.elapsed = seconds_since(t0);
    const int left = p.planned - p.done;
    p.eta = p.done > 0 ? p.elapsed / p.done * left : -1;
  }

  /// Appends a finished trial to results.jsonl, counts it and reports progress.
  void record(const TrialRecord& rec, ResultsFile& results, BatchRunStats& stats, const BatchRunOptions& run) {
    results.append(rec);
    ++stats.recorded;
    ++p.done;
    if (rec.status != "ok") {
      ++stats.failed;
      ++p.failed;
    }
    update_times();
    p.last = &rec;
    if (run.progress) run.progress(p);
    p.last = nullptr;
  }
};

/// A trial running in a child process.
struct Child {
  pid_t pid = -1;
  int fd = -1;      // read end of the pipe the child writes its record to
  int trial = -1;
  std::string out;  // what it has written so far
};

/// Why a child ended without a record, in words.
std::string describe_exit(int status) {
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    const char* name = ::strsignal(sig);
    return "the trial's process was killed by signal " + std::to_string(sig) + " (" + (name ? name : "unknown") + ")";
  }
  if (WIFEXITED(status)) return "the trial's process exited with code " + std::to_string(WEXITSTATUS(status)) + " without a result";
  return "the trial's process ended without a result";
}

/// In the child: run one trial and write its record line to `fd`, then leave without running
/// the parent's destructors or atexit handlers.
[[noreturn]] void child_main(pid_t parent, int fd, const Scenario& scenario, const ModelMap& models, int trial, std::uint64_t seed,
                             const TrialOptions& options, const std::string& fingerprint) {
  // die with the batch: a killed batch must not leave trials running on their own
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(3);
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  std::signal(SIGPIPE, SIG_DFL);
  // one trial per core: J trials at once already fill J cores
  set_worker_threads(1);
  if (const char* crash = std::getenv(kCrashTrialVariable); crash && *crash && std::atoi(crash) == trial) std::raise(SIGSEGV);
  const TrialRecord rec = run_trial(scenario, models, trial, seed, options, fingerprint);
  const std::string line = to_json_line(rec);
  const char* p = line.data();
  std::size_t left = line.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) ::_exit(4);
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  ::_exit(0);
}

BatchRunStats run_in_processes(const Scenario& scenario, const ModelMap& models, const std::vector<int>& trials, std::uint64_t base_seed,
                               const TrialOptions& options, const std::string& fingerprint, ResultsFile& results,
                               const BatchRunOptions& run, Tally& tally) {
  BatchRunStats stats;
  std::deque<int> pending(trials.begin(), trials.end());
  std::vector<Child> running;
  const pid_t self = ::getpid();
  const auto stopping = [&] { return run.stop && run.stop->load(std::memory_order_relaxed); };

  const auto finish = [&](Child& c) {
    int status = 0;
    while (::waitpid(c.pid, &status, 0) < 0 && errno == EINTR) {
    }
    ::close(c.fd);
    // abandoned, or stopped along with the batch (Ctrl-C reaches the whole process group, a
    // scheduler's SIGTERM every process): not recorded, so the trial runs again on resume
    const bool stopped_too =
        WIFSIGNALED(status) && (WTERMSIG(status) == SIGINT || WTERMSIG(status) == SIGTERM || WTERMSIG(status) == SIGHUP);
    if (stopping() || stopped_too) return;
    TrialRecord rec;
    bool parsed = false;
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0 && !c.out.empty()) {
      try {
        rec = parse_trial_line(c.out);
        parsed = true;
      } catch (const Error&) {
      }
    }
    if (!parsed) rec = failed_trial(scenario, c.trial, trial_seed(base_seed, c.trial), fingerprint, describe_exit(status));
    tally.record(rec, results, stats, run);
  };

  while ((!pending.empty() && !stopping()) || !running.empty()) {
    // start trials while there is room
    while (!stopping() && !pending.empty() && static_cast<int>(running.size()) < run.jobs) {
      const int trial = pending.front();
      int fds[2];
      if (::pipe2(fds, O_CLOEXEC) != 0) throw Error(std::string("batch: cannot create a pipe: ") + std::strerror(errno));
      const pid_t pid = ::fork();
      if (pid < 0) {
        ::close(fds[0]);
        ::close(fds[1]);
        throw Error(std::string("batch: cannot start a process for a trial: ") + std::strerror(errno));
      }
      if (pid == 0) {
        ::close(fds[0]);
        child_main(self, fds[1], scenario, models, trial, trial_seed(base_seed, trial), options, fingerprint);
      }
      ::close(fds[1]);
      pending.pop_front();
      running.push_back({pid, fds[0], trial, {}});
    }
    if (stopping()) {
      // abandon what is running: kill it and record nothing
      for (auto& c : running) ::kill(c.pid, SIGKILL);
      for (auto& c : running) finish(c);
      running.clear();
      break;
    }
    // wait for output from any child, or half a second for a progress update
    std::vector<pollfd> polls;
    for (const auto& c : running) polls.push_back({c.fd, POLLIN, 0});
    const int n = ::poll(polls.data(), polls.size(), 500);
    if (n < 0 && errno != EINTR) throw Error(std::string("batch: poll failed: ") + std::strerror(errno));
    for (std::size_t i = running.size(); i-- > 0;) {
      if (n <= 0 || !(polls[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      char buf[4096];
      const ssize_t got = ::read(running[i].fd, buf, sizeof buf);
      if (got > 0) {
        running[i].out.append(buf, static_cast<std::size_t>(got));
        continue;
      }
      if (got < 0 && errno == EINTR) continue;
      // end of file: the child is done (or dead)
      Child c = std::move(running[i]);
      running.erase(running.begin() + static_cast<std::ptrdiff_t>(i));
      tally.p.running = static_cast<int>(running.size());
      finish(c);
    }
    tally.p.running = static_cast<int>(running.size());
    if (run.progress && seconds_since(tally.last_report) > 0.5) {
      tally.last_report = Clock::now();
      tally.update_times();
      run.progress(tally.p);
    }
  }
  stats.interrupted = stats.recorded < static_cast<int>(trials.size());
  return stats;
}

BatchRunStats run_in_threads(const Scenario& scenario, const ModelMap& models, const std::vector<int>& trials, std::uint64_t base_seed,
                             const TrialOptions& options, const std::string& fingerprint, ResultsFile& results,
                             const BatchRunOptions& run, Tally& tally) {
  BatchRunStats stats;
  std::mutex mutex;
  std::size_t next = 0;
  const auto worker = [&] {
    for (;;) {
      int trial;
      {
        std::lock_guard lock(mutex);
        if (next >= trials.size() || (run.stop && run.stop->load())) return;
        trial = trials[next++];
        ++tally.p.running;
      }
      const TrialRecord rec = run_trial(scenario, models, trial, trial_seed(base_seed, trial), options, fingerprint);
      std::lock_guard lock(mutex);
      --tally.p.running;
      tally.record(rec, results, stats, run);
    }
  };
  std::vector<std::thread> threads;
  threads.reserve(static_cast<std::size_t>(run.jobs));
  for (int j = 0; j < run.jobs; ++j) threads.push_back(start_named_thread("batch-trials", worker));
  for (auto& t : threads) t.join();
  stats.interrupted = stats.recorded < static_cast<int>(trials.size());
  return stats;
}

}  // namespace

BatchRunStats run_batch_trials(const Scenario& scenario, const ModelMap& models, const std::vector<int>& trials, std::uint64_t base_seed,
                               const TrialOptions& options, const std::string& fingerprint, ResultsFile& results,
                               const BatchRunOptions& run) {
  Tally tally;
  tally.p.planned = static_cast<int>(trials.size());
  tally.jobs = std::max(1, run.jobs);
  BatchRunOptions r = run;
  r.jobs = tally.jobs;
  BatchRunStats stats = r.isolation == Isolation::process
                            ? run_in_processes(scenario, models, trials, base_seed, options, fingerprint, results, r, tally)
                            : run_in_threads(scenario, models, trials, base_seed, options, fingerprint, results, r, tally);
  stats.elapsed = seconds_since(tally.t0);
  return stats;
}

}  // namespace rescuesim
