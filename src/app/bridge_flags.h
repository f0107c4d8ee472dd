#pragma once
/// Command-line flags that attach bridges (ROS 1, ROS 2, Foxglove, MCAP recording) to a
/// simulation, shared by `rescuesim run` and `rescuesim replay`.

#include <CLI/CLI.hpp>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bus/bridge.h"

namespace rescuesim {
struct Scenario;
struct WorldSpec;
}  // namespace rescuesim

namespace rescuesim::app {

struct BridgeFlags {
  bool ros1 = false, ros2 = false;
  bool use_sim_time = false;
  std::string ros2_distro = "jazzy";   ///< humble, iron, jazzy, kilted or rolling
  std::string sim_services_ns = "/";  ///< --sim-services-ns: where the Simulation Interfaces services live
  std::optional<int> ros_domain;
  bool lockstep = false;          ///< with a ROS or Foxglove bridge: step as fast as possible anyway
  bool keep_controllers = false;  ///< with a ROS or Foxglove bridge: keep the built-in controllers
  std::optional<int> foxglove;    ///< --foxglove[=PORT]: serve the Foxglove WebSocket protocol on this port
  std::string foxglove_host = "127.0.0.1";  ///< interface the Foxglove server listens on
  std::string record;             ///< --record FILE.mcap: record every topic (not a live transport: runs stay lockstep)
  double record_chunk_seconds = 1.0;       ///< --record-chunk-seconds (rescuesim run): sim-time budget of a chunk
  double record_chunk_wall_seconds = 1.0;  ///< --record-chunk-wall-seconds (rescuesim run): wall-time budget (realtime runs)

  /// True when a live transport (ROS or Foxglove) is attached: runs default to realtime,
  /// until Ctrl-C, with the built-in controllers off.
  bool live() const { return ros1 || ros2 || foxglove.has_value(); }
};

/// Registers the bridge flags on a subcommand.
void add_bridge_flags(CLI::App* cmd, BridgeFlags& flags);
/// The run a recording describes (scenario text, world, seed), so `rescuesim replay` can
/// rebuild it; the scenario's mode also makes recording lossless (lockstep) or bounded (realtime).
struct RunContext {
  const Scenario* scenario = nullptr;
  const WorldSpec* world = nullptr;
  bool cameras = true;  ///< false: recorded with --no-cameras
};

/// The bridges asked for, not yet started. Throws Error (exit 2) for one this build lacks.
std::vector<std::unique_ptr<Bridge>> make_bridges(const BridgeFlags& flags, const RunContext& run = {});

}  // namespace rescuesim::app
