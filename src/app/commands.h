#pragma once
/// The `rescuesim` command-line tool: one function per subcommand registers its options on
/// the CLI11 app and returns the action to run after parsing.

#include <CLI/CLI.hpp>

#include <functional>
#include <string>
#include <vector>

#include "world/mission_spec.h"
#include "world/world_spec.h"

namespace rescuesim::app {

/// Exit codes: 0 success, 1 a run failed, 2 bad usage or bad input.
inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitBadInput = 2;

using Action = std::function<int()>;

void add_check_command(CLI::App& app, Action& action);
void add_maze_command(CLI::App& app, Action& action);
void add_arena_command(CLI::App& app, Action& action);
void add_trial_terrain_command(CLI::App& app, Action& action);
void add_run_command(CLI::App& app, Action& action);
/// `bench` (and the hidden `bench-probe`): runs rescuesim-bench beside this program with `args`,
/// this program's own arguments without argv[0] (cmd_bench.cpp says why it is a program of its own).
void add_bench_command(CLI::App& app, Action& action, const std::vector<std::string>& args);
void add_snapshot_command(CLI::App& app, Action& action);
void add_view_command(CLI::App& app, Action& action);
void add_replay_command(CLI::App& app, Action& action);
void add_batch_command(CLI::App& app, Action& action);
void add_recover_command(CLI::App& app, Action& action);

/// Several lines describing a world: size, counts of each kind, starts.
std::string world_summary(const WorldSpec& world);
/// Several lines describing a mission: its rules, its radio model, its base stations.
std::string mission_summary(const MissionSpec& mission, const WorldSpec& world);
/// Prints diagnostics to stderr, one per line, indented.
void print_diagnostics(const Diagnostics& d);

}  // namespace rescuesim::app
