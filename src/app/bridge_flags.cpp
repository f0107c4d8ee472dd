#include "app/bridge_flags.h"

#include "core/error.h"
#ifdef RESCUESIM_HAS_ROS1
#include "bridges/ros1/ros1_bridge.h"
#endif
#ifdef RESCUESIM_HAS_ROS2
#include "bridges/ros2/ros2_bridge.h"
#endif
#ifdef RESCUESIM_HAS_FOXGLOVE
#include "bridges/foxglove/foxglove_bridge.h"
#endif
#ifdef RESCUESIM_HAS_MCAP
#include "bridges/mcap/mcap_bridge.h"
#include "run_record/run_record.h"
#endif

namespace rescuesim::app {

void add_bridge_flags(CLI::App* cmd, BridgeFlags& f) {
  cmd->add_flag("--ros1", f.ros1,
                "be a ROS 1 node: register with ROS_MASTER_URI, publish sensors, /tf, /clock; take cmd_vel (docs/ros.md)");
  cmd->add_flag("--ros2", f.ros2, "be a ROS 2 participant on ROS_DOMAIN_ID (Cyclone DDS, ROS 2 wire conventions; docs/ros.md)");
  cmd->add_flag("--use-sim-time", f.use_sim_time, "ROS 1: set the /use_sim_time parameter so nodes follow /clock");
  cmd->add_option("--ros2-distro", f.ros2_distro,
                  "the ROS 2 distribution of the peers (default jazzy): humble (24-byte Gids in ros_discovery_info), iron, "
                  "jazzy, kilted (16-byte Gids; sensor_msgs/Range with variance), rolling (also the Simulation Interfaces "
                  "2.x layouts)")
      ->check(CLI::IsMember({"humble", "iron", "jazzy", "kilted", "rolling"}));
  cmd->add_option("--sim-services-ns", f.sim_services_ns,
                  "ROS 2: the namespace of the Simulation Interfaces services and the simulate_steps action (default /: "
                  "/reset_simulation, as Isaac Sim and O3DE; /gzserver puts them where Gazebo does; docs/ros.md)");
  cmd->add_option("--ros-domain", f.ros_domain, "ROS 2 domain id (default: ROS_DOMAIN_ID, else 0)")->check(CLI::Range(0, 232));
  cmd->add_option("--foxglove", f.foxglove,
                  "serve Foxglove/Lichtblick on ws://HOST:PORT (default port 8765; 0 picks a free one, logged at --log-level info; "
                  "docs/foxglove.md)")
      ->expected(0, 1)
      ->default_str("8765")
      ->check(CLI::Range(0, 65535));
  cmd->add_option("--foxglove-host", f.foxglove_host,
                  "interface the Foxglove server listens on (default 127.0.0.1; 0.0.0.0 for every one)");
  cmd->add_option("--record", f.record,
                  "record every topic to this MCAP file (ros2 profile, zstd chunks, indexed: open it in Foxglove or "
                  "'rescuesim replay' it; docs/recording.md)");
  cmd->add_flag("--lockstep", f.lockstep, "with a ROS or Foxglove bridge: step as fast as possible instead of realtime");
  cmd->add_flag("--keep-controllers", f.keep_controllers,
                "with a ROS or Foxglove bridge: keep the scenario's built-in controllers driving");
}

std::vector<std::unique_ptr<Bridge>> make_bridges(const BridgeFlags& f, [[maybe_unused]] const RunContext& run) {
  std::vector<std::unique_ptr<Bridge>> bridges;
  if (f.ros1) {
#ifdef RESCUESIM_HAS_ROS1
    Ros1Options o;
    o.use_sim_time = f.use_sim_time;
    bridges.push_back(make_ros1_bridge(o));
#else
    throw Error("--ros1: this rescuesim was built without the ROS 1 bridge (roscpp not found at build time; "
                "run scripts/install-deps.sh and rebuild)");
#endif
  }
  if (f.ros2) {
#ifdef RESCUESIM_HAS_ROS2
    Ros2Options o;
    if (f.ros_domain) o.domain_id = *f.ros_domain;
    o.distro = f.ros2_distro == "humble" ? Ros2Distro::humble : Ros2Distro::iron_or_newer;
    o.sim_interfaces_v2 = f.ros2_distro == "rolling";
    o.sim_services_ns = f.sim_services_ns;
    bridges.push_back(make_ros2_bridge(o));
#else
    throw Error("--ros2: this rescuesim was built without the ROS 2 bridge (Cyclone DDS not found at build time; "
                "run scripts/install-deps.sh and rebuild)");
#endif
  }
  if (f.foxglove) {
#ifdef RESCUESIM_HAS_FOXGLOVE
    FoxgloveOptions o;
    o.port = *f.foxglove;
    o.host = f.foxglove_host;
    bridges.push_back(make_foxglove_bridge(o));
#else
    throw Error("--foxglove: this rescuesim was built without the Foxglove bridge (Boost.Beast headers not found at build time; "
                "run scripts/install-deps.sh and rebuild)");
#endif
  }
  if (!f.record.empty()) {
#ifdef RESCUESIM_HAS_MCAP
    McapOptions o;
    o.path = f.record;
    o.library = std::string("rescuesim ") + RESCUESIM_VERSION;
    o.chunk_seconds = f.record_chunk_seconds;
    o.chunk_wall_seconds = f.record_chunk_wall_seconds;
    if (run.scenario && run.world) describe_run(o, *run.scenario, *run.world, run.cameras, RESCUESIM_VERSION);
    bridges.push_back(make_mcap_recorder(o));
#else
    throw Error("--record: this rescuesim was built without the MCAP recorder (libzstd/liblz4 not found at build time; "
                "run scripts/install-deps.sh and rebuild)");
#endif
  }
  return bridges;
}

}  // namespace rescuesim::app
