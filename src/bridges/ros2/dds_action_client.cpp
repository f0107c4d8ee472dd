#include "bridges/ros2/dds_action_client.h"

#include <thread>

namespace rescuesim::ros2 {

ActionClient::ActionClient(DdsParticipant& dds, ActionTopics topics)
    : dds_(dds),
      topics_(std::move(topics)),
      send_goal_(dds, topics_.send_goal),
      cancel_goal_(dds, topics_.cancel_goal),
      get_result_(dds, topics_.get_result) {
  feedback_reader_ = dds_.create_raw_reader(topics_.feedback_topic, topics_.feedback_type, action_feedback_qos(), {},
                                            DdsParticipant::Wake::own);
  status_reader_ = dds_.create_raw_reader(topics_.status_topic, topics_.status_type, action_status_qos(), {},
                                          DdsParticipant::Wake::own);
}

bool ActionClient::server_ready() const {
  return send_goal_.server_ready() && cancel_goal_.server_ready() && get_result_.server_ready() &&
         dds_.matched_writers(feedback_reader_) > 0 && dds_.matched_writers(status_reader_) > 0;
}

bool ActionClient::wait_for_server(std::chrono::milliseconds timeout) const {
  const auto give_up = std::chrono::steady_clock::now() + timeout;
  while (!server_ready()) {
    if (std::chrono::steady_clock::now() >= give_up) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return true;
}

std::optional<SendGoalResponse> ActionClient::send_goal(const GoalId& id, std::span<const std::uint8_t> goal,
                                                        std::chrono::milliseconds timeout, std::string* why) {
  const auto reply = send_goal_.call(encode_send_goal_request(id, goal), timeout, why);
  if (!reply) return std::nullopt;
  return decode_send_goal_response(*reply);
}

std::optional<CancelResponse> ActionClient::cancel(const GoalInfo& which, std::chrono::milliseconds timeout, std::string* why) {
  const auto reply = cancel_goal_.call(encode_cancel_request(which), timeout, why);
  if (!reply) return std::nullopt;
  return decode_cancel_response(*reply);
}

std::optional<std::int64_t> ActionClient::request_result(const GoalId& id, std::string* why) {
  return get_result_.send(encode_result_request(id), why);
}

std::optional<std::vector<std::uint8_t>> ActionClient::wait_result(std::int64_t seq, std::chrono::milliseconds timeout, std::string* why) {
  return get_result_.wait_reply(seq, timeout, why);
}

std::optional<std::vector<std::uint8_t>> ActionClient::get_result(const GoalId& id, std::chrono::milliseconds timeout, std::string* why) {
  const auto seq = request_result(id, why);
  if (!seq) return std::nullopt;
  return wait_result(*seq, timeout, why);
}

std::vector<FeedbackMessage> ActionClient::take_feedback() {
  std::vector<FeedbackMessage> out;
  dds_.take(feedback_reader_, [&](std::span<const std::uint8_t> bytes) { out.push_back(decode_feedback_message(bytes)); });
  return out;
}

std::vector<std::vector<GoalStatus>> ActionClient::take_status() {
  std::vector<std::vector<GoalStatus>> out;
  dds_.take(status_reader_, [&](std::span<const std::uint8_t> bytes) { out.push_back(decode_status_array(bytes)); });
  return out;
}

bool ActionClient::wait_feedback(std::chrono::milliseconds timeout) { return dds_.wait_reader(feedback_reader_, timeout); }
bool ActionClient::wait_status(std::chrono::milliseconds timeout) { return dds_.wait_reader(status_reader_, timeout); }

}  // namespace rescuesim::ros2
