#pragma once
/// What every rescuesim program's main() does after declaring its command line (the CLI and
/// rescuesim-bench): parse it, apply the global --log-level and --threads, run the chosen
/// command, and turn what goes wrong into a message and an exit code.

#include <string>

#include "app/commands.h"

namespace rescuesim::app {

/// Parses `argv` into `app` (a parse error or --help prints and exits 0 or 2), sets the log
/// level and the worker threads (0: every core), checks RESCUESIM_DATA_DIR when it is set, and
/// runs `action` (nothing chosen: 0). A rescuesim::Error is bad input (2), any other exception
/// a failure (1), each printed after `program`.
int run_program(CLI::App& app, int argc, char** argv, const std::string& log_level, const int& threads, const Action& action,
                const char* program);

}  // namespace rescuesim::app
