#pragma once
/// Command-line flags that attach bridges (ROS 1, ROS 2, Foxglove, MCAP recording) to a
/// simulation, shared by `rescuesim run` and `rescuesim replay`.

#include <CLI/CLI.hpp>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sim/bridge.h"

namespace rescuesim::app {

struct BridgeFlags {
  bool ros1 = false, ros2 = false;
  bool use_sim_time = false;
  std::string ros2_distro = "humble";
  std::optional<int> ros_domain;
  bool lockstep = false;          ///< with a ROS or Foxglove bridge: step as fast as possible anyway
  bool keep_controllers = false;  ///< with a ROS or Foxglove bridge: keep the built-in controllers

  /// True when a live transport (ROS or Foxglove) is attached: runs default to realtime,
  /// until Ctrl-C, with the built-in controllers off.
  bool live() const { return ros1 || ros2; }
};

/// Registers the bridge flags on a subcommand.
void add_bridge_flags(CLI::App* cmd, BridgeFlags& flags);
/// The bridges asked for, not yet started. Throws Error (exit 2) for one this build lacks.
std::vector<std::unique_ptr<Bridge>> make_bridges(const BridgeFlags& flags);

}  // namespace rescuesim::app
