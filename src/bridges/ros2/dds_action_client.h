#pragma once
/// The calling side of a ROS 2 action on a DdsParticipant, as rclcpp_action's client speaks it:
/// three ServiceClients (send_goal, cancel_goal, get_result) and readers of the feedback and
/// status topics. For tests and `rescuesim bench`; one thread at a time.

#include <chrono>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "bridges/ros2/dds_action_wire.h"
#include "bridges/ros2/dds_participant.h"
#include "bridges/ros2/dds_services.h"

namespace rescuesim::ros2 {

class ActionClient {
 public:
  ActionClient(DdsParticipant& dds, ActionTopics topics);

  /// True when the three services are served and the feedback and status topics have a writer.
  bool server_ready() const;
  bool wait_for_server(std::chrono::milliseconds timeout) const;

  /// Sends goal `goal` (`<A>_Goal` as a CDR message) as goal `id`; the server's answer, or nullopt
  /// with `why` on timeout. Throws Error when the answer does not decode.
  std::optional<SendGoalResponse> send_goal(const GoalId& id, std::span<const std::uint8_t> goal, std::chrono::milliseconds timeout,
                                            std::string* why = nullptr);
  /// Asks to cancel `which` (a goal id and/or a stamp; both zero: every goal).
  std::optional<CancelResponse> cancel(const GoalInfo& which, std::chrono::milliseconds timeout, std::string* why = nullptr);
  /// Sends a get_result request for goal `id` without waiting; its sequence number.
  std::optional<std::int64_t> request_result(const GoalId& id, std::string* why = nullptr);
  /// The `<A>_GetResult_Response_` (a CDR message: status, result) for request `seq`.
  std::optional<std::vector<std::uint8_t>> wait_result(std::int64_t seq, std::chrono::milliseconds timeout, std::string* why = nullptr);
  /// request_result() then wait_result().
  std::optional<std::vector<std::uint8_t>> get_result(const GoalId& id, std::chrono::milliseconds timeout, std::string* why = nullptr);

  /// Feedback messages that arrived since the last call (for every goal; see FeedbackMessage::id).
  std::vector<FeedbackMessage> take_feedback();
  /// Status arrays that arrived since the last call, oldest first.
  std::vector<std::vector<GoalStatus>> take_status();
  /// Waits up to `timeout` for feedback (status) to arrive; true when some is waiting.
  bool wait_feedback(std::chrono::milliseconds timeout);
  bool wait_status(std::chrono::milliseconds timeout);

  const ActionTopics& topics() const { return topics_; }

 private:
  DdsParticipant& dds_;
  ActionTopics topics_;
  ServiceClient send_goal_, cancel_goal_, get_result_;
  int feedback_reader_ = -1, status_reader_ = -1;
};

}  // namespace rescuesim::ros2
