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

/// The same, fitted to `robot`: the explorer (not the wall follower) models its victim camera
/// (victim_camera_look). A robot other than the built-in one (a URDF robot) also gets a radius
/// from the footprint of its collision shapes around the root link, distances to walls that
/// scale with it, and speeds within its drive's limits; the built-in rescue robot keeps the
/// geometry and speeds of builtin_explorer_config(controller).
autonomy::ExplorerConfig builtin_explorer_config(const std::string& controller, const RobotSpec& robot);

/// How the explorer models a robot's victim camera (its last thermal camera, rendered or not:
/// line-of-sight detection looks through it too): its fan, and with `swing` the nearest
/// position-controlled joint above it turning about the vertical, which the explorer swings to
/// look from side to side. Without `swing` (a controller that cannot command the joint, such as
/// the ROS navigation node) the camera is taken to stay where it starts, and the explorer turns
/// the whole robot to look. Disabled for a robot without a thermal camera.
autonomy::ExplorerLookConfig victim_camera_look(const RobotSpec& robot, bool swing = true);

/// The radius of a robot's footprint: the farthest collision point from the root link's
/// vertical axis, at the starting joint positions (m).
double footprint_radius(const RobotSpec& robot);
}  // namespace rescuesim
