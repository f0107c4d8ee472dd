#pragma once
/// The hook through which the ROS 2 bridge offers a run's control surface: at start() the bridge
/// makes its ServiceRegistry (service_registry.h) and calls register_control_services() once,
/// before it announces its node, so that every service and action registered here is served on
/// the bridge's receive thread and listed under the node in ros_discovery_info. The
/// simulation_interfaces services, the SimulateSteps action and the parameter services are
/// wired here (through host.control(), bus/sim_control.h, which is null when the run cannot be
/// controlled).

#include <cstdint>
#include <functional>

#include "bridges/ros2/ros2_bridge.h"
#include "bridges/ros2/service_registry.h"
#include "bus/bridge_host.h"

namespace rescuesim::ros2 {

/// Registers the run's services and actions on `services`. Called by the bridge's start(), on the
/// thread that steps; may throw Error (the bridge does not start then). Returns how many requests
/// so far reached a service whole but did not decode as its type (the registry counts those that
/// were not even whole: ServiceRegistry::malformed).
std::function<std::uint64_t()> register_control_services(ServiceRegistry& services, BridgeHost& host, const Ros2Options& options);

}  // namespace rescuesim::ros2
