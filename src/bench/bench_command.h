#pragma once
/// The `bench` command of the rescuesim-bench program: its options and its JSON report (every
/// speed figure beside a raw baseline measured in the same run). Users type `rescuesim bench`;
/// the CLI forwards it here (app/cmd_bench.cpp).

#include <CLI/CLI.hpp>

#include "app/commands.h"

namespace rescuesim::bench {

/// Registers `bench` and the hidden `bench-probe` (the ROS figures' subscriber process) on
/// rescuesim-bench's command line; the parsed command's work goes into `action`.
void add_bench_command(CLI::App& app, app::Action& action);

}  // namespace rescuesim::bench
