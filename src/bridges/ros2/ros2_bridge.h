#pragma once
/// The ROS 2 bridge: a Cyclone DDS participant that follows ROS 2's conventions (topic `/scan`
/// is DDS topic `rt/scan` of type `sensor_msgs::msg::dds_::LaserScan_`, XCDR1 little endian),
/// so ROS 2 nodes on rmw_cyclonedds or rmw_fastrtps see its topics and its node. See docs/ros.md.

#include <memory>
#include <string>

#include "bus/bridge.h"

namespace rescuesim {

/// Size of rmw_dds_common Gid in ros_discovery_info: 24 bytes up to Humble, 16 from Iron on.
enum class Ros2Distro { humble, iron_or_newer };

struct Ros2Options {
  int domain_id = -1;              ///< -1: ROS_DOMAIN_ID from the environment, else 0
  std::string node_name = "rescuesim";
  std::string node_namespace = "/";
  Ros2Distro distro = Ros2Distro::humble;
  std::size_t queue_size = 64;     ///< per topic: most messages buffered before the oldest is dropped
                                   ///< (a topic buffers at most about one second of its messages)
  /// Where the Simulation Interfaces services and the SimulateSteps action live: "/" (root, as
  /// Isaac Sim and O3DE serve them) or a namespace ("/gzserver", as Gazebo's ros_gz_sim does).
  std::string sim_services_ns = "/";
  /// The Simulation Interfaces wire layout: 1.x (Humble, Jazzy, Kilted) or 2.x (Rolling), which
  /// differ in SetEntityState's request and in Spawnable.
  bool sim_interfaces_v2 = false;
};

/// Throws rescuesim::Error on start() when the DDS participant cannot be created.
std::unique_ptr<Bridge> make_ros2_bridge(const Ros2Options& options = {});

}  // namespace rescuesim
