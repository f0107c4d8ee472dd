#include "bridges/ros2/dds_action_wire.h"

#include <algorithm>
#include <cstring>
#include <limits>

#include "bridges/common/cdr_stream.h"
#include "core/error.h"

namespace rescuesim::ros2 {

namespace {

constexpr std::size_t kUuid = 16;

// the ROS 2 transport reads these in the byte order their encapsulation names
constexpr auto kEither = cdr::Encapsulations::either_endian;
constexpr std::size_t kHeader = cdr::kEncapsulationSize;

// a message (encapsulation header, then payload) whose payload starts with a UUID: the id and
// the rest as a message of its own (same header; same alignment, as the UUID is 16 bytes)
GoalId split_uuid(std::span<const std::uint8_t> body, const char* what, std::vector<std::uint8_t>* rest) {
  cdr::Reader in(body, what, kEither);
  GoalId id{};
  in.octets("goal_id", id);
  if (rest) {
    rest->assign(body.begin(), body.begin() + kHeader);
    rest->insert(rest->end(), body.begin() + kHeader + kUuid, body.end());
  }
  return id;
}

std::vector<std::uint8_t> join_uuid(const GoalId& id, std::span<const std::uint8_t> message, const char* what) {
  if (!cdr::xcdr1_byte_order(message)) {
    throw Error(std::string(what) + ": not a CDR message (no XCDR1 encapsulation header)");
  }
  std::vector<std::uint8_t> out(message.size() + kUuid);
  std::memcpy(out.data(), message.data(), kHeader);
  std::memcpy(out.data() + kHeader, id.data(), kUuid);
  std::memcpy(out.data() + kHeader + kUuid, message.data() + kHeader, message.size() - kHeader);
  return out;
}

void put_info(cdr::Writer& w, const GoalInfo& g) {
  w.octets("goal_id.uuid", g.id);
  w.value("stamp.sec", g.stamp.sec);
  w.value("stamp.nanosec", g.stamp.nanosec);
}

void get_info(cdr::Reader& in, GoalInfo& g) {
  in.octets("goal_id.uuid", g.id);
  in.value("stamp.sec", g.stamp.sec);
  in.value("stamp.nanosec", g.stamp.nanosec);
}

}  // namespace

Stamp Stamp::from_ns(std::int64_t ns) {
  constexpr std::int64_t kNs = 1'000'000'000;
  std::int64_t sec = ns / kNs, rem = ns % kNs;
  if (rem < 0) --sec, rem += kNs;
  sec = std::clamp<std::int64_t>(sec, std::numeric_limits<std::int32_t>::min(), std::numeric_limits<std::int32_t>::max());
  return {static_cast<std::int32_t>(sec), static_cast<std::uint32_t>(rem)};
}

ActionTopics action_topics(const std::string& ros_action, const std::string& action_type) {
  const std::string dds = dds_type_name(action_type);  // "pkg::action::dds_::Name_"
  if (action_type.find("/action/") == std::string::npos) {
    throw Error("action type '" + action_type + "': expected package/action/Name");
  }
  ActionTopics t;
  t.name = absolute_ros_name(ros_action);
  // rcl_action names.c: services and topics under <action>/_action/; rosidl's types <A>_SendGoal_Request_ ...
  t.send_goal = service_topics_for_dds_base(t.name + "/_action/send_goal", dds + "SendGoal_");
  t.cancel_goal = service_topics_for_dds_base(t.name + "/_action/cancel_goal", "action_msgs::srv::dds_::CancelGoal_");
  t.get_result = service_topics_for_dds_base(t.name + "/_action/get_result", dds + "GetResult_");
  t.feedback_topic = dds_topic_name(t.name + "/_action/feedback");
  t.feedback_type = dds + "FeedbackMessage_";
  t.status_topic = dds_topic_name(t.name + "/_action/status");
  t.status_type = "action_msgs::msg::dds_::GoalStatusArray_";
  return t;
}

EndpointQos action_status_qos() {
  EndpointQos q;
  q.reliability = Reliability::reliable;
  q.durability = Durability::transient_local;
  q.depth = 1;
  return q;
}

EndpointQos action_feedback_qos() {
  EndpointQos q;
  q.reliability = Reliability::reliable;
  q.durability = Durability::volatile_local;
  q.depth = 10;
  return q;
}

std::vector<std::uint8_t> encode_send_goal_request(const GoalId& id, std::span<const std::uint8_t> goal) {
  return join_uuid(id, goal, "SendGoal request: goal");
}

SendGoalRequest decode_send_goal_request(std::span<const std::uint8_t> body) {
  SendGoalRequest r;
  r.id = split_uuid(body, "SendGoal request", &r.goal);
  return r;
}

std::vector<std::uint8_t> encode_send_goal_response(const SendGoalResponse& r) {
  std::vector<std::uint8_t> out;
  cdr::Writer w(out, "SendGoal response");
  w.value("accepted", r.accepted);
  w.value("stamp.sec", r.stamp.sec);
  w.value("stamp.nanosec", r.stamp.nanosec);
  return out;
}

SendGoalResponse decode_send_goal_response(std::span<const std::uint8_t> body) {
  cdr::Reader in(body, "SendGoal response", kEither);
  SendGoalResponse r;
  in.value("accepted", r.accepted);
  in.value("stamp.sec", r.stamp.sec);
  in.value("stamp.nanosec", r.stamp.nanosec);
  in.finish();
  return r;
}

std::vector<std::uint8_t> encode_cancel_request(const GoalInfo& info) {
  std::vector<std::uint8_t> out;
  cdr::Writer w(out, "action_msgs/CancelGoal request");
  put_info(w, info);
  return out;
}

GoalInfo decode_cancel_request(std::span<const std::uint8_t> body) {
  cdr::Reader in(body, "action_msgs/CancelGoal request", kEither);
  GoalInfo g;
  get_info(in, g);
  in.finish();
  return g;
}

std::vector<std::uint8_t> encode_cancel_response(const CancelResponse& r) {
  std::vector<std::uint8_t> out;
  cdr::Writer w(out, "action_msgs/CancelGoal response");
  w.value("return_code", r.return_code);
  w.elements("goals_canceling", r.goals_canceling, 24, cdr::kUnbounded, [&](const GoalInfo& g) { put_info(w, g); });
  return out;
}

CancelResponse decode_cancel_response(std::span<const std::uint8_t> body) {
  cdr::Reader in(body, "action_msgs/CancelGoal response", kEither);
  CancelResponse r;
  in.value("return_code", r.return_code);
  // a count the bytes left cannot hold (24 bytes a GoalInfo) is refused before anything is allocated
  in.elements("goals_canceling", r.goals_canceling, 24, cdr::kUnbounded, [&](GoalInfo& g) { get_info(in, g); });
  in.finish();
  return r;
}

std::vector<std::uint8_t> encode_result_request(const GoalId& id) {
  std::vector<std::uint8_t> out;
  cdr::Writer w(out, "GetResult request");
  w.octets("goal_id", id);
  return out;
}

GoalId decode_result_request(std::span<const std::uint8_t> body) {
  cdr::Reader in(body, "GetResult request", kEither);
  GoalId id{};
  in.octets("goal_id", id);
  in.finish();
  return id;
}

void set_result_status(std::vector<std::uint8_t>& response, std::int8_t status) {
  if (response.size() <= kHeader || !cdr::xcdr1_byte_order(response)) {
    throw Error("GetResult response: not a CDR message with an int8 status first (" + std::to_string(response.size()) + " bytes)");
  }
  response[kHeader] = static_cast<std::uint8_t>(status);
}

std::int8_t result_status(std::span<const std::uint8_t> response) {
  cdr::Reader in(response, "GetResult response", kEither);
  std::int8_t status = 0;
  in.value("status", status);
  return status;
}

std::vector<std::uint8_t> encode_feedback_message(const GoalId& id, std::span<const std::uint8_t> feedback) {
  return join_uuid(id, feedback, "FeedbackMessage: feedback");
}

FeedbackMessage decode_feedback_message(std::span<const std::uint8_t> body) {
  FeedbackMessage m;
  m.id = split_uuid(body, "FeedbackMessage", &m.feedback);
  return m;
}

std::vector<std::uint8_t> encode_status_array(const std::vector<GoalStatus>& list) {
  std::vector<std::uint8_t> out;
  cdr::Writer w(out, "action_msgs/GoalStatusArray");
  w.elements("status_list", list, 25, cdr::kUnbounded, [&](const GoalStatus& s) {
    put_info(w, s.info);
    w.value("status", s.status);
  });
  return out;
}

std::vector<GoalStatus> decode_status_array(std::span<const std::uint8_t> body) {
  cdr::Reader in(body, "action_msgs/GoalStatusArray", kEither);
  std::vector<GoalStatus> out;
  // a count the bytes left cannot hold (at least 25 bytes a GoalStatus) is refused before anything is allocated
  in.elements("status_list", out, 25, cdr::kUnbounded, [&](GoalStatus& s) {
    get_info(in, s.info);
    in.value("status", s.status);
  });
  in.finish();
  return out;
}

}  // namespace rescuesim::ros2
