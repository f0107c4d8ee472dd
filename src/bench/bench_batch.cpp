#include "bench/bench_batch.h"

#include <sys/resource.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "robots/rescue_robot.h"
#include "batch/batch_results.h"
#include "batch/batch_runner.h"

namespace rescuesim::bench {

namespace {

using json = nlohmann::ordered_json;

/// One batch run into a scratch folder: trials per hour and what the trials simulated.
/// CPU seconds (user + system) used so far by this process's finished children, or by itself.
double cpu_seconds(int who) {
  rusage ru{};
  ::getrusage(who, &ru);
  return ru.ru_utime.tv_sec + ru.ru_stime.tv_sec + 1e-6 * (ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
}

json measure(const Scenario& scenario, int trials, int jobs, Isolation isolation) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("rescuesim-bench-batch-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const ModelMap models = builtin_models();
  TrialOptions o;
  o.stop_when_all_found = false;  // three-minute trials, as the target is stated
  std::vector<int> plan;
  for (int i = 0; i < trials; ++i) plan.push_back(i);
  BatchRunStats stats;
  double sim_time = 0;
  int failed = 0;
  // trials in child processes count as children's CPU time, in-process ones as our own
  const int who = isolation == Isolation::process ? RUSAGE_CHILDREN : RUSAGE_SELF;
  const double cpu0 = cpu_seconds(who);
  {
    ResultsFile results(dir);
    BatchRunOptions ro;
    ro.jobs = jobs;
    ro.isolation = isolation;
    stats = run_batch_trials(scenario, models, plan, scenario.seed, o, "rs1-bench", results, ro);
    for (const auto& [t, r] : results.load().records) {
      sim_time += r.sim_time;
      failed += r.status != "ok";
    }
  }
  const double cpu = cpu_seconds(who) - cpu0;
  fs::remove_all(dir);
  return {{"jobs", jobs},
          {"isolation", isolation == Isolation::process ? "process per trial" : "in process"},
          {"trials", stats.recorded},
          {"failed", failed},
          {"wall_time_s", stats.elapsed},
          {"mean_sim_time_s", stats.recorded > 0 ? sim_time / stats.recorded : 0.0},
          {"trials_per_hour", stats.elapsed > 0 ? stats.recorded / stats.elapsed * 3600 : 0.0},
          {"cpu_s_per_trial", stats.recorded > 0 ? cpu / stats.recorded : 0.0},
          {"note_cpu", "trials per hour one core would give from CPU time alone (less sensitive to other load on the machine)"},
          {"trials_per_hour_per_core_from_cpu_time", cpu > 0 ? stats.recorded / cpu * 3600 : 0.0}};
}

}  // namespace

json bench_batch(const Scenario& scenario, int trials) {
  json j;
  j["scenario"] = scenario.name;
  j["trial_sim_time_s"] = scenario.duration;
  j["cameras"] = false;
  j["stop_when_all_found"] = false;
  std::fprintf(stderr, "bench: batch, %d trials in this process ...\n", trials);
  const json base = measure(scenario, trials, 1, Isolation::thread);
  std::fprintf(stderr, "bench: batch, %d trials at --jobs 1 ...\n", trials);
  const json one = measure(scenario, trials, 1, Isolation::process);
  std::fprintf(stderr, "bench: batch, %d trials at --jobs 2 ...\n", 2 * trials);
  const json two = measure(scenario, 2 * trials, 2, Isolation::process);
  const double b = base["trials_per_hour"].get<double>();
  const auto figure = [&](const json& m, double target) {
    json f = m;
    f["baseline_trials_per_hour"] = b;
    f["baseline_is"] = "the same trials one after another in this process (no child processes)";
    f["ratio"] = b > 0 ? m["trials_per_hour"].get<double>() / b : 0.0;
    f["target_trials_per_hour"] = target;
    f["meets_target"] = m["trials_per_hour"].get<double>() >= target;
    return f;
  };
  j["jobs_1"] = figure(one, 500);
  j["jobs_2"] = figure(two, 1000);
  j["in_process"] = base;
  return j;
}

json bench_python_step() {
#if defined(RESCUESIM_PYTHON_EXECUTABLE) && defined(RESCUESIM_PYTHON_DIR)
  std::fprintf(stderr, "bench: Python step overhead ...\n");
  const std::string cmd = std::string("PYTHONPATH='") + RESCUESIM_PYTHON_DIR + "' '" + RESCUESIM_PYTHON_EXECUTABLE +
                          "' -m rescuesim.bench_step 2>&1";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(::popen(cmd.c_str(), "r"), ::pclose);
  if (!pipe) return {{"error", "cannot start " + cmd}};
  std::string out;
  char buf[4096];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, pipe.get())) > 0) out.append(buf, n);
  try {
    return json::parse(out);
  } catch (const json::parse_error&) {
    return {{"error", "rescuesim.bench_step failed: " + out}};
  }
#else
  return {{"error", "the Python API was not built (RESCUESIM_PYTHON)"}};
#endif
}

}  // namespace rescuesim::bench
