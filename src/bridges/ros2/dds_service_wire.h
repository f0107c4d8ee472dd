#pragma once
/// ROS 2 services on plain DDS as rmw_cyclonedds_cpp puts them on the wire (its src/serdata.hpp,
/// Serialization.cpp and rmw_node.cpp): the names, the 16-byte request header and the
/// client/service ids in endpoint USER_DATA. Pure functions, no DDS types; see
/// /work/shared/domain/ros2-sim-interfaces.md section 3.
///
/// A request (or reply) sample is: the 4-byte encapsulation header, `uint64 guid`, `int64 seq`
/// (in the byte order the encapsulation names), then the request (reply) body. The reply echoes
/// the request's guid and seq. The bridge hands bodies around as standalone CDR messages: the
/// request's encapsulation header followed by the body bytes. That is exact, not an
/// approximation: XCDR1 aligns each primitive of size n (1, 2, 4 or 8) to an offset that is a
/// multiple of n, counted from the end of the encapsulation header. The header takes offsets
/// 0..15 (guid at 0 and seq at 8, both already aligned), so a body field at body offset k sits
/// at stream offset 16 + k, and since 16 is a multiple of 8 (and so of 4, 2 and 1),
/// (16 + k) mod n = k mod n for every n: each field gets the same padding in both places. The
/// body bytes are therefore exactly the standalone encoding of the body, and a codec that
/// counts alignment from offset 0 decodes them as they are. The encapsulation's options (its
/// last two bytes, which may announce padding at the end of the message) describe the end of
/// the message, which the header does not move, so they are kept too. A body may end in up to 3
/// zero bytes that no options announce: rmw_cyclonedds rounds every sample up to a multiple of 4
/// (serdata_rmw::resize), and since 4 + 16 is a multiple of 4 too, the body then ends on one;
/// the codecs accept that (bridges/common/cdr_stream.h).

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "bridges/ros2/ros2_conventions.h"

namespace rescuesim::ros2 {

/// rmw_cyclonedds's cdds_request_header_t: the client's id (its request writer's instance
/// handle in rmw_cyclonedds; any number unique to the client) and the request's sequence number.
struct RequestHeader {
  std::uint64_t guid = 0;
  std::int64_t seq = 0;
  bool operator==(const RequestHeader&) const = default;
};

/// Bytes of the request header after the encapsulation header.
inline constexpr std::size_t kRequestHeaderBytes = 16;

/// A request or reply sample split into its header and its body (a standalone CDR message:
/// the sample's encapsulation header, then the bytes after the request header).
struct ServiceSample {
  RequestHeader header;
  std::vector<std::uint8_t> body;
};

/// Splits a request or reply sample. Returns nullopt, with `why` set, when the bytes are shorter
/// than the encapsulation and request headers or the encapsulation is not XCDR1 (00 00 or 00 01).
std::optional<ServiceSample> split_service_sample(std::span<const std::uint8_t> sample, std::string* why = nullptr);

/// The sample for `header` and `body` (a CDR message with its encapsulation header; the header
/// is written in the byte order that encapsulation names). Throws Error when `body` has no XCDR1
/// encapsulation header.
std::vector<std::uint8_t> join_service_sample(const RequestHeader& header, std::span<const std::uint8_t> body);

/// The DDS topics and types of one service.
struct ServiceTopics {
  std::string name;           ///< ROS name, "/reset_simulation"
  std::string request_topic;  ///< "rq/reset_simulationRequest"
  std::string reply_topic;    ///< "rr/reset_simulationReply"
  std::string request_type;   ///< "simulation_interfaces::srv::dds_::ResetSimulation_Request_"
  std::string reply_type;     ///< "simulation_interfaces::srv::dds_::ResetSimulation_Response_"
};

/// The absolute ROS name for `name` ("reset_simulation" and "/reset_simulation" give
/// "/reset_simulation"). Throws Error for an empty name, "//", a trailing '/', or a character
/// other than letters, digits, '_' and '/'.
std::string absolute_ros_name(const std::string& name);

/// The DDS type name of a ROS 2 interface type: "pkg/msg/Name" -> "pkg::msg::dds_::Name_"
/// (also srv and action). Throws Error when `ros_type` is not three names joined by '/'.
std::string dds_type_name(const std::string& ros_type);

/// Topics and types of service `ros_service` of type `srv_type` ("simulation_interfaces/srv/ResetSimulation").
ServiceTopics service_topics(const std::string& ros_service, const std::string& srv_type);
/// Topics for `ros_service` whose DDS types are `<dds_type_base>Request_` and `<dds_type_base>Response_`
/// ("action_msgs::srv::dds_::CancelGoal_" gives "action_msgs::srv::dds_::CancelGoal_Request_").
ServiceTopics service_topics_for_dds_base(const std::string& ros_service, const std::string& dds_type_base);

/// The QoS of service endpoints: rmw_qos_profile_services_default (reliable, volatile, keep last 10).
EndpointQos service_qos();

/// A client or service id as rmw_cyclonedds makes it: the participant's 12-byte GUID prefix,
/// then `counter` big endian, as hex bytes joined by '.', the first printed two wide (space
/// filled, as its std::setw(2) does), the rest without leading zeros: " 1.f.0.a. ... .0.0.0.2".
std::string client_service_id(const Guid& participant, std::uint32_t counter);
/// USER_DATA of a service's endpoints: "serviceid=<id>;".
std::string service_user_data(const std::string& id);
/// USER_DATA of a client's endpoints: "clientid=<id>;".
std::string client_user_data(const std::string& id);

/// The value of `key` in USER_DATA of the form "k1=v1;k2=v2;", or nullopt.
std::optional<std::string> user_data_value(std::string_view user_data, std::string_view key);

}  // namespace rescuesim::ros2
