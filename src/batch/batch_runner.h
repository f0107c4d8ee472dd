#pragma once
/// Runs a batch's trials J at a time and records each in results.jsonl as it finishes. By
/// default every trial runs in a child process of its own (fork), so a trial that crashes —
/// even with a segfault — is recorded as failed and the batch goes on; trials never share
/// memory, so a trial's result does not depend on how many run at once.

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "batch/batch_results.h"
#include "batch/batch_trial.h"

namespace rescuesim {

/// Where trials run.
enum class Isolation {
  process,  ///< a child process per trial (a crash fails only that trial)
  thread,   ///< threads of this process (no fork; a crash ends the batch)
};

/// How far a batch has come, for progress displays.
struct BatchProgress {
  int planned = 0;         ///< trials this run set out to do
  int done = 0;            ///< of those, recorded
  int failed = 0;          ///< of those recorded, failed
  int running = 0;
  double elapsed = 0;      ///< s of wall time since the run started
  double eta = -1;         ///< s of wall time still expected; -1 until a trial has finished
  const TrialRecord* last = nullptr;  ///< the record just written, or null for a timed update
};

/// Settings of a batch run.
struct BatchRunOptions {
  int jobs = 1;                               ///< trials at once
  Isolation isolation = Isolation::process;
  const std::atomic<bool>* stop = nullptr;    ///< set to stop: trials still running are abandoned (not recorded);
                                              ///< so are trials whose process dies of SIGINT, SIGTERM or SIGHUP
  std::function<void(const BatchProgress&)> progress;  ///< after each trial and about twice a second
};

/// What a batch run did.
struct BatchRunStats {
  int recorded = 0;          ///< trials recorded by this run
  int failed = 0;            ///< of those, failed
  bool interrupted = false;  ///< stopped before every planned trial was recorded
  double elapsed = 0;        ///< s of wall time
};

/// Runs `trials` (indices into the batch, each with seed trial_seed(base_seed, i)) and appends
/// a record for each to `results` as soon as it finishes (in finishing order).
BatchRunStats run_batch_trials(const Scenario& scenario, const ModelMap& models, const std::vector<int>& trials,
                               std::uint64_t base_seed, const TrialOptions& options, const std::string& fingerprint,
                               ResultsFile& results, const BatchRunOptions& run);

/// Environment variable naming a trial whose child process crashes on purpose (SIGSEGV) as it
/// starts: how the tests check that a crash fails only its trial. Ignored with Isolation::thread.
inline constexpr const char* kCrashTrialVariable = "RESCUESIM_BATCH_CRASH_TRIAL";

}  // namespace rescuesim
