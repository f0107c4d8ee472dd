#pragma once
/// The settings of the built-in controllers on the rescue robot, in one place: a run's session
/// uses them, and so does the ROS 1 navigation node (examples/ros1/nav), so that the explorer
/// driving the robot in-process and over ROS is the same code with the same configuration.

#include <string>

#include "autonomy/explorer.h"
#include "world/robot_spec.h"

namespace rescuesim {

/// The explorer settings of a robot whose scenario controller is `controller`: "explorer"
/// (wall following + A* to frontiers) or "wall_follower" (pure wall following, never plans).
/// Throws Error for any other name.
autonomy::ExplorerConfig builtin_explorer_config(const std::string& controller);

/// The same, fitted to a robot other than the built-in one (a URDF robot): its radius is the
/// footprint of its collision shapes around the root link, distances to walls scale with it,
/// and speeds stay within its drive's limits. The built-in rescue robot gets exactly
/// builtin_explorer_config(controller).
autonomy::ExplorerConfig builtin_explorer_config(const std::string& controller, const RobotSpec& robot);

/// How the explorer models a robot's victim camera (its last thermal camera, rendered or not: line-of-sight detection looks through it too): its fan,
/// and the nearest position-controlled joint above it turning about the vertical, which the
/// explorer swings to look from side to side. Disabled for a robot without a thermal camera.
autonomy::ExplorerLookConfig victim_camera_look(const RobotSpec& robot);

/// The radius of a robot's footprint: the farthest collision point from the root link's
/// vertical axis, at the starting joint positions (m).
double footprint_radius(const RobotSpec& robot);
}  // namespace rescuesim
