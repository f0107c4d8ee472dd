// rescuesim bench: runs rescuesim-bench, the benchmarks' own program (src/bench), from this
// program's folder with the same arguments.
//
// Why a program of its own: the benchmarks (the whole-run figures, the ROS and control clients,
// the soak, the scale and cold start figures) are code that running a scenario never needs, and
// as part of this executable `make run` compiled every file of them. As rescuesim-bench they are built by `make
// bench`, `make build` and the tests, installed beside `rescuesim` (so in the .deb too), and
// `rescuesim bench ...` stays the command users type. The bench starts `rescuesim run` and
// `rescuesim --version` (cold start) as this program, the one beside it, and its ROS figures'
// subscriber (`bench-probe`) as itself. Without rescuesim-bench (a build of the `rescuesim`
// target alone, or RESCUESIM_BENCH=OFF) the command says how to build it and exits 2.

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "app/commands.h"
#include "app/data_dir.h"

namespace rescuesim::app {

namespace {

namespace fs = std::filesystem;

constexpr const char* kBenchProgram = "rescuesim-bench";

/// Replaces this process with rescuesim-bench given `args` (this program's arguments, without
/// argv[0]); returns only when it cannot, with the exit code.
int exec_bench_program(const std::vector<std::string>& args) {
  const fs::path program = sibling_program(kBenchProgram);
  std::error_code ec;
  if (program.empty() || !fs::exists(program, ec)) {
    std::fprintf(stderr,
                 "rescuesim: bench: the benchmarks are a program of their own, %s, and it is not beside this one (%s).\n"
                 "Build it with `make bench` (which then runs every benchmark) or `cmake --build build --target %s`.\n",
                 kBenchProgram, program.empty() ? "this program's folder is unknown" : program.c_str(), kBenchProgram);
    return kExitBadInput;
  }
  std::vector<char*> argv;
  std::string name = program.string();
  argv.push_back(name.data());
  std::vector<std::string> copies = args;
  for (std::string& a : copies) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::fflush(stdout);
  std::fflush(stderr);
  ::execv(program.c_str(), argv.data());
  std::fprintf(stderr, "rescuesim: bench: cannot run %s: %s\n", program.c_str(), std::strerror(errno));
  return kExitFailure;
}

}  // namespace

void add_bench_command(CLI::App& app, Action& action, const std::vector<std::string>& args) {
  const std::pair<const char*, const char*> commands[] = {
      {"bench", "Measure speed and memory, each figure beside a raw baseline from the same run (runs rescuesim-bench)"},
      {"bench-probe", ""}};  // the ROS figures' subscriber process (internal, hidden)
  for (const auto& [name, description] : commands) {
    CLI::App* cmd = app.add_subcommand(name, description);
    if (*description == '\0') cmd->group("");
    // every argument after the command, --help included, is rescuesim-bench's to read
    cmd->set_help_flag();
    cmd->prefix_command();
    cmd->final_callback([&action, args] { action = [args] { return exec_bench_program(args); }; });
  }
}

}  // namespace rescuesim::app
