#pragma once
/// The ROS 1 bridge: the simulator becomes a ROS 1 node (Debian's roscpp) in its own process.
/// It registers with the master at ROS_MASTER_URI, publishes every Bus topic with the same
/// name and type (TF, /clock, sensors, a URDF robot's latched robot_description), and subscribes
/// to each robot's cmd_vel (geometry_msgs/Twist or geometry_msgs/TwistStamped, whichever the
/// publisher uses, one type at a time: ros1_velocity.h; a stamp ahead of sim time is refused), head/command
/// (std_msgs/Float64MultiArray) and, for robots with commandable joints, joint_command
/// (sensor_msgs/JointState). A robot's description also goes to the parameter of the same name
/// (/robot_description, or /<robot>/robot_description when namespaced), where ROS 1 tools look
/// for it. It offers /reset_simulation, /pause_physics, /unpause_physics (std_srvs/Empty, as
/// gazebo_ros) and /step_simulation (std_srvs/Trigger) through the host's control surface
/// (ros1_sim_services.h; refused when the host has none). See docs/ros.md.
///
/// Messages travel as bytes made by rescuesim's own serialiser (msgs/serialize.h), advertised
/// with its MD5 and definition, so rostopic and rosbag check them like any other node's. The
/// simulation never waits for ROS: messages queue (bounded, oldest dropped) for a publisher
/// thread; commands are decoded on a spinner thread and applied at the next step boundary. A
/// master that goes away is noticed within master_check_period; the node registers everything
/// again when it (or a new master at the same URI) answers. One ROS 1 bridge per process.

#include <memory>
#include <string>

#include "bus/bridge.h"

namespace rescuesim {

struct Ros1Options {
  std::string node_name = "rescuesim";
  bool use_sim_time = false;       ///< set the /use_sim_time parameter to true on start
  /// per topic: most messages buffered before the oldest of that topic is dropped
  /// (bridges/common/outbox.h)
  std::size_t queue_size = 64;
  double master_timeout = 3.0;     ///< s to wait for the master on start() before giving up
  double master_check_period = 1.0;  ///< s between checks that the master is (still) there
  double service_timeout = 5.0;    ///< s a service call waits for the simulation's answer before it fails
};

/// Throws rescuesim::Error on start() when no master answers (the message names ROS_MASTER_URI).
std::unique_ptr<Bridge> make_ros1_bridge(const Ros1Options& options = {});

}  // namespace rescuesim
