#pragma once
/// The settings of the built-in controllers on the rescue robot, in one place: a run's session
/// uses them, and so does the ROS 1 navigation node (examples/ros1/nav), so that the explorer
/// driving the robot in-process and over ROS is the same code with the same configuration.

#include <string>

#include "autonomy/explorer.h"

namespace rescuesim {

/// The explorer settings of a robot whose scenario controller is `controller`: "explorer"
/// (wall following + A* to frontiers) or "wall_follower" (pure wall following, never plans).
/// Throws Error for any other name.
autonomy::ExplorerConfig builtin_explorer_config(const std::string& controller);

}  // namespace rescuesim
