#include "bridges/ros2/dds_action_wire.h"

#include <algorithm>
#include <cstring>
#include <limits>

#include "bridges/ros2/cdr_bytes.h"
#include "core/error.h"

namespace rescuesim::ros2 {

namespace {

constexpr std::size_t kUuid = 16;

// a message (encapsulation header, then payload) whose payload starts with a UUID: the id and
// the rest as a message of its own (same header; same alignment, as the UUID is 16 bytes)
GoalId split_uuid(std::span<const std::uint8_t> body, const char* what, std::vector<std::uint8_t>* rest) {
  cdr::Reader in(body, what);
  GoalId id{};
  const auto b = in.bytes(kUuid, "goal_id");
  std::copy(b.begin(), b.end(), id.begin());
  if (rest) {
    rest->assign(body.begin(), body.begin() + cdr::kEncapsulation);
    rest->insert(rest->end(), body.begin() + cdr::kEncapsulation + kUuid, body.end());
  }
  return id;
}

std::vector<std::uint8_t> join_uuid(const GoalId& id, std::span<const std::uint8_t> message, const char* what) {
  if (message.size() < cdr::kEncapsulation || message[0] != 0x00 || message[1] > 0x01) {
    throw Error(std::string(what) + ": not a CDR message (no XCDR1 encapsulation header)");
  }
  std::vector<std::uint8_t> out(message.size() + kUuid);
  std::memcpy(out.data(), message.data(), cdr::kEncapsulation);
  std::memcpy(out.data() + cdr::kEncapsulation, id.data(), kUuid);
  std::memcpy(out.data() + cdr::kEncapsulation + kUuid, message.data() + cdr::kEncapsulation, message.size() - cdr::kEncapsulation);
  return out;
}

void put_info(cdr::Writer& w, const GoalInfo& g) {
  w.bytes(g.id);
  w.put(g.stamp.sec);
  w.put(g.stamp.nanosec);
}

GoalInfo get_info(cdr::Reader& in) {
  GoalInfo g;
  const auto b = in.bytes(kUuid, "goal_id.uuid");
  std::copy(b.begin(), b.end(), g.id.begin());
  g.stamp.sec = in.get<std::int32_t>("stamp.sec");
  g.stamp.nanosec = in.get<std::uint32_t>("stamp.nanosec");
  return g;
}

// a sequence count no larger than the bytes left could hold, `min_size` bytes an element
std::uint32_t get_count(cdr::Reader& in, const char* field, std::size_t min_size) {
  const std::uint32_t n = in.get<std::uint32_t>(field);
  if (std::uint64_t{n} * min_size > in.remaining()) {
    in.fail(field, std::to_string(n) + " elements cannot fit in the " + std::to_string(in.remaining()) + " bytes left");
  }
  return n;
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
  cdr::Writer w;
  w.put<std::uint8_t>(r.accepted ? 1 : 0);
  w.put(r.stamp.sec);
  w.put(r.stamp.nanosec);
  return w.take();
}

SendGoalResponse decode_send_goal_response(std::span<const std::uint8_t> body) {
  cdr::Reader in(body, "SendGoal response");
  SendGoalResponse r;
  r.accepted = in.get<std::uint8_t>("accepted") != 0;
  r.stamp.sec = in.get<std::int32_t>("stamp.sec");
  r.stamp.nanosec = in.get<std::uint32_t>("stamp.nanosec");
  in.finish();
  return r;
}

std::vector<std::uint8_t> encode_cancel_request(const GoalInfo& info) {
  cdr::Writer w;
  put_info(w, info);
  return w.take();
}

GoalInfo decode_cancel_request(std::span<const std::uint8_t> body) {
  cdr::Reader in(body, "action_msgs/CancelGoal request");
  const GoalInfo g = get_info(in);
  in.finish();
  return g;
}

std::vector<std::uint8_t> encode_cancel_response(const CancelResponse& r) {
  cdr::Writer w;
  w.put(r.return_code);
  w.put(static_cast<std::uint32_t>(r.goals_canceling.size()));
  for (const GoalInfo& g : r.goals_canceling) put_info(w, g);
  return w.take();
}

CancelResponse decode_cancel_response(std::span<const std::uint8_t> body) {
  cdr::Reader in(body, "action_msgs/CancelGoal response");
  CancelResponse r;
  r.return_code = in.get<std::int8_t>("return_code");
  const std::uint32_t n = get_count(in, "goals_canceling", 24);
  for (std::uint32_t i = 0; i < n; ++i) r.goals_canceling.push_back(get_info(in));
  in.finish();
  return r;
}

std::vector<std::uint8_t> encode_result_request(const GoalId& id) {
  cdr::Writer w;
  w.bytes(id);
  return w.take();
}

GoalId decode_result_request(std::span<const std::uint8_t> body) {
  cdr::Reader in(body, "GetResult request");
  GoalId id{};
  const auto b = in.bytes(kUuid, "goal_id");
  std::copy(b.begin(), b.end(), id.begin());
  in.finish();
  return id;
}

void set_result_status(std::vector<std::uint8_t>& response, std::int8_t status) {
  if (response.size() <= cdr::kEncapsulation || response[0] != 0x00 || response[1] > 0x01) {
    throw Error("GetResult response: not a CDR message with an int8 status first (" + std::to_string(response.size()) + " bytes)");
  }
  response[cdr::kEncapsulation] = static_cast<std::uint8_t>(status);
}

std::int8_t result_status(std::span<const std::uint8_t> response) {
  cdr::Reader in(response, "GetResult response");
  return in.get<std::int8_t>("status");
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
  cdr::Writer w;
  w.put(static_cast<std::uint32_t>(list.size()));
  for (const GoalStatus& s : list) {
    put_info(w, s.info);
    w.put(s.status);
  }
  return w.take();
}

std::vector<GoalStatus> decode_status_array(std::span<const std::uint8_t> body) {
  cdr::Reader in(body, "action_msgs/GoalStatusArray");
  const std::uint32_t n = get_count(in, "status_list", 25);
  std::vector<GoalStatus> out(n);
  for (GoalStatus& s : out) {
    s.info = get_info(in);
    s.status = in.get<std::int8_t>("status");
  }
  in.finish();
  return out;
}

}  // namespace rescuesim::ros2
