#pragma once
/// A bare ROS 1 subscriber for `rescuesim bench`: a node of its own (in a process of its own,
/// as roscpp allows one node per process) that subscribes to topics of any type and reports the
/// header stamp of every message it receives, so the bench can time sim → subscriber delivery.
/// It reads only the stamp: the std_msgs/Header that leads every stamped ROS 1 message.

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace rescuesim {

/// Called on the probe's thread for each message: the index of its topic in the list given
/// to run_ros1_probe and its header stamp (ns of sim time).
using Ros1ProbeCallback = std::function<void(std::size_t topic, std::int64_t stamp_ns)>;

/// Registers node `node_name` with the master at ROS_MASTER_URI (ROS_HOSTNAME / ROS_IP as the
/// bridge reads them), subscribes to `topics` whatever their type, then calls `ready` once and
/// `on_message` per message until `stop` is set or `seconds` of wall time pass. Throws
/// rescuesim::Error when no master answers within 5 s.
void run_ros1_probe(const std::string& node_name, const std::vector<std::string>& topics, const Ros1ProbeCallback& on_message,
                    const std::function<void()>& ready, const std::atomic<bool>& stop, double seconds);

}  // namespace rescuesim
