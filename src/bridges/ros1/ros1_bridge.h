#pragma once
/// The ROS 1 bridge: the simulator becomes a ROS 1 node (Debian's roscpp) in its own process.
/// It registers with the master at ROS_MASTER_URI, publishes every Bus topic with the same
/// name and type (TF, /clock, sensors), and subscribes to each robot's cmd_vel
/// (geometry_msgs/Twist) and head/command (std_msgs/Float64MultiArray). See docs/ros.md.

#include <memory>
#include <string>

#include "sim/bridge.h"

namespace rescuesim {

struct Ros1Options {
  std::string node_name = "rescuesim";
  bool use_sim_time = false;       ///< set the /use_sim_time parameter to true on start
  std::size_t queue_size = 64;     ///< messages buffered per bridge before the oldest is dropped
};

/// Throws rescuesim::Error on start() when no master answers (the message names ROS_MASTER_URI).
std::unique_ptr<Bridge> make_ros1_bridge(const Ros1Options& options = {});

}  // namespace rescuesim
