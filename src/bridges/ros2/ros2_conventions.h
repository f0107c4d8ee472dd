#pragma once
/// How ROS 2 (rmw_cyclonedds, rmw_fastrtps) maps its graph onto plain DDS, as far as the bridge
/// needs it: topic names, QoS, the domain id, participant USER_DATA, and the discovery message
/// that makes a participant show up as a node (`ros2 node list`). Pure functions, no DDS types.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "bridges/ros2/ros2_bridge.h"
#include "bus/bus.h"

namespace rescuesim::ros2 {

/// A DDS GUID: 12-byte participant prefix and 4-byte entity id, as dds_get_guid gives it.
using Guid = std::array<std::uint8_t, 16>;

enum class Reliability { reliable, best_effort };
enum class Durability { volatile_local, transient_local };

/// QoS of one DDS reader or writer; history is always KEEP_LAST `depth`.
struct EndpointQos {
  Reliability reliability = Reliability::reliable;
  Durability durability = Durability::volatile_local;
  int depth = 10;
  bool operator==(const EndpointQos&) const = default;
};

/// How many messages of `topic` the bridge buffers before it drops the oldest: about one second
/// of them (at least 4), and never more than `max` (images are large; /clock is not).
std::size_t queue_capacity(const Topic& topic, std::size_t max);

/// The DDS topic of a ROS 2 topic: "/scan" -> "rt/scan", "/robot2/cmd_vel" -> "rt/robot2/cmd_vel".
std::string dds_topic_name(const std::string& ros_topic);

/// The writer QoS for a Bus topic: RELIABLE + VOLATILE + KEEP_LAST 10 (a reliable writer also
/// matches best-effort readers, such as ROS 2's SensorDataQoS); latched topics (/tf_static,
/// robot_description) RELIABLE + TRANSIENT_LOCAL depth 1, like tf2's StaticBroadcasterQoS and
/// robot_state_publisher's robot_description; /clock depth 1.
EndpointQos writer_qos(const Topic& topic);

/// The reader QoS for commands (/cmd_vel, /head/command, /joint_command): BEST_EFFORT +
/// VOLATILE depth 10, which matches both reliable and best-effort ROS 2 publishers.
EndpointQos command_reader_qos();

/// The discovery topic's QoS: RELIABLE + TRANSIENT_LOCAL + KEEP_LAST 1 (as rmw_dds_common).
EndpointQos discovery_qos();

/// DDS topic and type of ROS 2's node discovery messages.
inline constexpr const char* kDiscoveryTopic = "ros_discovery_info";
inline constexpr const char* kDiscoveryType = "rmw_dds_common::msg::dds_::ParticipantEntitiesInfo_";

/// The domain: `requested` when >= 0, else ROS_DOMAIN_ID from the environment, else 0. Throws
/// Error when ROS_DOMAIN_ID is not a whole number in 0..232 (DDS's port mapping limit).
int resolve_domain(int requested);

/// Participant USER_DATA as rmw sets it: "enclave=/;".
std::string participant_user_data();

/// Bytes of a Gid in rmw_dds_common: 24 up to Humble, 16 from Iron on.
std::size_t gid_size(Ros2Distro distro);

/// True when adapt_to_distro changes the bytes of `m` for `distro` (the bridge then encodes
/// them itself rather than share another bridge's).
bool distro_changes(const msg::Message& m, Ros2Distro distro);
/// Adapts our serialiser's CDR (ROS 2 Humble layouts) to `distro` in place: from Iron on,
/// sensor_msgs/Range ends with `float32 variance`, which gets 0 (unknown).
void adapt_to_distro(const msg::Message& m, Ros2Distro distro, std::vector<std::uint8_t>& cdr);

/// One ROS node and the DDS entities that belong to it.
struct NodeEntities {
  std::string node_namespace = "/";
  std::string node_name;
  std::vector<Guid> readers;
  std::vector<Guid> writers;
};

/// rmw_dds_common/ParticipantEntitiesInfo as XCDR1 with its encapsulation header: the
/// participant's GID and its nodes; each GID is the 16-byte GUID zero-padded to `gid_bytes`.
std::vector<std::uint8_t> encode_discovery_info(const Guid& participant, const std::vector<NodeEntities>& nodes,
                                                std::size_t gid_bytes);

}  // namespace rescuesim::ros2
