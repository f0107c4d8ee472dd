#pragma once
/// ROS 2 actions on plain DDS (rcl_action's names, rosidl's generated types): three services
/// and two topics under `<action>/_action/`, and the few action_msgs messages the transport
/// encodes itself (UUID = uint8[16], builtin_interfaces/Time = int32 sec + uint32 nanosec,
/// GoalInfo, GoalStatus(Array), CancelGoal). Goal, feedback and result bodies stay bytes: their
/// codecs live elsewhere. Pure functions; decoders throw Error naming the field that is wrong.
///
/// Where the action's own messages meet the transport's fields:
/// - `<A>_SendGoal_Request_` = UUID goal_id, then the goal; `<A>_FeedbackMessage_` = UUID
///   goal_id, then the feedback. The UUID is 16 bytes, so (as for the service request header,
///   dds_service_wire.h) the goal or feedback that follows is byte for byte its standalone
///   encoding: split and join move bytes only.
/// - `<A>_GetResult_Response_` = int8 status, then the result. A one-byte field does shift the
///   result's alignment, so the transport cannot glue a standalone result behind it; instead the
///   result codec encodes the whole response (with any status) and the transport overwrites its
///   status, the first byte after the encapsulation header.

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "bridges/ros2/dds_service_wire.h"

namespace rescuesim::ros2 {

/// unique_identifier_msgs/UUID: a goal's id.
using GoalId = std::array<std::uint8_t, 16>;

/// builtin_interfaces/Time.
struct Stamp {
  std::int32_t sec = 0;
  std::uint32_t nanosec = 0;
  static Stamp from_ns(std::int64_t ns);
  std::int64_t ns() const { return std::int64_t{sec} * 1'000'000'000 + nanosec; }
  bool operator==(const Stamp&) const = default;
};

/// action_msgs/GoalInfo.
struct GoalInfo {
  GoalId id{};
  Stamp stamp;
  bool operator==(const GoalInfo&) const = default;
};

/// action_msgs/GoalStatus constants.
namespace goal_status {
inline constexpr std::int8_t kUnknown = 0, kAccepted = 1, kExecuting = 2, kCanceling = 3, kSucceeded = 4, kCanceled = 5,
                             kAborted = 6;
/// SUCCEEDED, CANCELED or ABORTED.
inline bool terminal(std::int8_t s) { return s == kSucceeded || s == kCanceled || s == kAborted; }
}  // namespace goal_status

/// action_msgs/GoalStatus.
struct GoalStatus {
  GoalInfo info;
  std::int8_t status = goal_status::kUnknown;
  bool operator==(const GoalStatus&) const = default;
};

/// action_msgs/srv/CancelGoal response codes.
namespace cancel_code {
inline constexpr std::int8_t kNone = 0, kRejected = 1, kUnknownGoalId = 2, kGoalTerminated = 3;
}

/// The DDS side of one action.
struct ActionTopics {
  std::string name;  ///< ROS name, "/simulate_steps"
  ServiceTopics send_goal, cancel_goal, get_result;
  std::string feedback_topic, feedback_type;  ///< "rt/simulate_steps/_action/feedback", "<pkg>::action::dds_::<A>_FeedbackMessage_"
  std::string status_topic, status_type;      ///< "rt/simulate_steps/_action/status", "action_msgs::msg::dds_::GoalStatusArray_"
};

/// Topics and types of action `ros_action` of type `action_type` ("simulation_interfaces/action/SimulateSteps").
/// Throws Error for a bad name or type.
ActionTopics action_topics(const std::string& ros_action, const std::string& action_type);

/// The QoS of the status topic: reliable, transient local, keep last 1 (rcl_action's default).
EndpointQos action_status_qos();
/// The QoS of the feedback topic: rmw_qos_profile_default (reliable, volatile, keep last 10).
EndpointQos action_feedback_qos();

/// A `<A>_SendGoal_Request_` body: the goal's id and the goal (a CDR message).
struct SendGoalRequest {
  GoalId id{};
  std::vector<std::uint8_t> goal;  ///< `<A>_Goal` as a CDR message
};
std::vector<std::uint8_t> encode_send_goal_request(const GoalId& id, std::span<const std::uint8_t> goal);
SendGoalRequest decode_send_goal_request(std::span<const std::uint8_t> body);

/// A `<A>_SendGoal_Response_` body: bool accepted, Time stamp.
struct SendGoalResponse {
  bool accepted = false;
  Stamp stamp;
};
std::vector<std::uint8_t> encode_send_goal_response(const SendGoalResponse& r);
SendGoalResponse decode_send_goal_response(std::span<const std::uint8_t> body);

/// action_msgs/srv/CancelGoal: request GoalInfo goal_info; response int8 return_code,
/// GoalInfo[] goals_canceling.
std::vector<std::uint8_t> encode_cancel_request(const GoalInfo& info);
GoalInfo decode_cancel_request(std::span<const std::uint8_t> body);
struct CancelResponse {
  std::int8_t return_code = cancel_code::kNone;
  std::vector<GoalInfo> goals_canceling;
};
std::vector<std::uint8_t> encode_cancel_response(const CancelResponse& r);
CancelResponse decode_cancel_response(std::span<const std::uint8_t> body);

/// A `<A>_GetResult_Request_` body: the goal's id.
std::vector<std::uint8_t> encode_result_request(const GoalId& id);
GoalId decode_result_request(std::span<const std::uint8_t> body);
/// Overwrites the status of a `<A>_GetResult_Response_` body (its first byte after the
/// encapsulation header). Throws Error when the body is too short to have one.
void set_result_status(std::vector<std::uint8_t>& response, std::int8_t status);
/// The status of a `<A>_GetResult_Response_` body.
std::int8_t result_status(std::span<const std::uint8_t> response);

/// A `<A>_FeedbackMessage_` body: the goal's id and the feedback (`<A>_Feedback`, a CDR message).
struct FeedbackMessage {
  GoalId id{};
  std::vector<std::uint8_t> feedback;
};
std::vector<std::uint8_t> encode_feedback_message(const GoalId& id, std::span<const std::uint8_t> feedback);
FeedbackMessage decode_feedback_message(std::span<const std::uint8_t> body);

/// action_msgs/GoalStatusArray: GoalStatus[] status_list.
std::vector<std::uint8_t> encode_status_array(const std::vector<GoalStatus>& list);
std::vector<GoalStatus> decode_status_array(std::span<const std::uint8_t> body);

}  // namespace rescuesim::ros2
