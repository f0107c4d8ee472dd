#pragma once
/// Where the ROS 1 node finds its master and under which host name it offers its own
/// connections, decided from the environment the way roscpp reads it, plus one rescuesim rule:
/// with neither ROS_HOSTNAME nor ROS_IP set and a master on this machine, the node calls itself
/// "localhost". (roscpp would otherwise advertise the machine's host name, which often does not
/// resolve in containers and on laptops; every peer of a loopback master is local anyway.)

#include <string>

namespace rescuesim {

/// What the ROS 1 bridge hands to ros::init.
struct Ros1Endpoint {
  std::string master_uri;   ///< e.g. "http://localhost:11311"
  std::string hostname;     ///< "localhost" when rescuesim chose it, "" when roscpp decides (ROS_HOSTNAME / ROS_IP / gethostname)
};

/// Resolves the endpoint from the values of ROS_MASTER_URI, ROS_HOSTNAME and ROS_IP (nullptr or
/// "" = unset). An unset master URI means http://localhost:11311, as roscore's default.
Ros1Endpoint resolve_ros1_endpoint(const char* master_uri_env, const char* hostname_env, const char* ip_env);

/// True when the URI's host is this machine by name or loopback address ("localhost",
/// "127.0.0.1", "[::1]", ...).
bool is_loopback_uri(const std::string& uri);

}  // namespace rescuesim
