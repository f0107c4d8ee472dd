#pragma once
/// Ground truth: the true pose of a robot's base link in the world, as a localisation system
/// with no error would report it, and the /tf transforms that put the robot where it really is.

#include <string>

#include "core/sim_time.h"
#include "msgs/messages.h"
#include "world/state.h"

namespace rescuesim {

/// The pose of `robot`'s base link in the world (State::robots[robot].base.X_WB), stamped
/// `stamp`, in frame "map" (the world frame is the map frame).
msg::PoseStamped sample_ground_truth(const State& state, RobotIndex robot, SimTime stamp);

/// Which transforms ground truth adds to /tf, and the (already namespaced) frames they join.
struct GroundTruthTf {
  std::string odom_frame;      ///< e.g. "odom" or "robot2/odom"
  std::string base_frame;      ///< the robot's root link, e.g. "base_link"
  bool odom_to_base = false;   ///< odom → base_frame is the true pose (instead of wheel odometry's)
  bool map_to_odom = false;    ///< map → odom such that map → odom → base_frame is the true pose
};

/// The transforms `tf` asks for, in this order: odom → base (pose X_WB), then map → odom
/// (X_WB · X_OB⁻¹, where X_OB is X_WB itself when odom_to_base, else the wheel odometry pose
/// State::robots[robot].odom). Empty when neither is asked for.
msg::TFMessage ground_truth_tf(const State& state, RobotIndex robot, SimTime stamp, const GroundTruthTf& tf);

}  // namespace rescuesim
