#pragma once
// rescuesim bench, ROS part: how long /scan and a 640x480 colour image take from the simulation
// to a subscriber in another process over ROS 1 and ROS 2 on loopback, and what attaching both
// bridges costs the real-time factor, beside the same run without bridges.

#include <CLI/CLI.hpp>

#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "import/scenario/scenario.h"

namespace rescuesim::bench {

struct BenchRosOptions {
  double latency_seconds = 5;   ///< wall (= sim) seconds of each realtime latency run
  double rtf_seconds = 20;      ///< sim seconds of each lockstep run with and without bridges
  int rtf_rounds = 3;           ///< runs with and without bridges, alternating (the best of each counts)
};

/// The ROS figures: latency (median, p99, count) per transport and topic, and the real-time
/// factor with --ros1 --ros2 beside the same run without them (subscribers on /scan and the
/// image: bridge_cost; on /scan alone: bridge_cost_scan_only). A transport that this build or
/// machine lacks (no bridge, no roscore) is reported as {"skipped": reason}, never an error.
nlohmann::ordered_json bench_ros(const Scenario& scenario, const ModelMap& models, const BenchRosOptions& options);

/// The hidden `bench-probe` subcommand of rescuesim-bench: the bench's subscriber process
/// (`rescuesim bench-probe` reaches it through the CLI's forwarding, app/cmd_bench.cpp).
void add_bench_probe_command(CLI::App& app, app::Action& action);

}  // namespace rescuesim::bench
