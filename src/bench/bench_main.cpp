// rescuesim-bench: the benchmarks' program. Users type `rescuesim bench ...`, which runs this
// program from the CLI's own folder with the same arguments (app/cmd_bench.cpp), so its command
// line is the CLI's: the global --log-level and --threads, then `bench` (or the hidden
// `bench-probe`, the ROS figures' subscriber process, which the bench starts as this program).

#include <cstdio>
#include <cstdlib>
#include <exception>

#include "app/commands.h"
#include "app/data_dir.h"
#include "app/program.h"
#include "bench/bench_command.h"
#include "core/error.h"
#include "core/log.h"
#include "core/memory.h"
#include "core/parallel.h"

using namespace rescuesim;

int main(int argc, char** argv) {
  tune_allocator_for_long_runs();
  app::set_program_path(argc > 0 ? argv[0] : nullptr);
  CLI::App app{"rescuesim-bench — the benchmarks of rescuesim; run as `rescuesim bench` (see 'rescuesim bench --help')", "rescuesim-bench"};
  app.set_version_flag("--version", std::string("rescuesim-bench ") + RESCUESIM_VERSION);
  app.require_subcommand(1);
  std::string log_level = "warn";
  app.add_option("--log-level", log_level, "trace, debug, info, warn, error or off")->capture_default_str();
  int threads = 0;
  app.add_option("--threads", threads, "worker threads for physics groups, ray sensors and built-in controllers (0 = every core)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1024));
  app::Action action;
  bench::add_bench_command(app, action);

  return app::run_program(app, argc, argv, log_level, threads, action, "rescuesim bench");
}
