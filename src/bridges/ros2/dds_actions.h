#pragma once
/// ROS 2 action servers on a DdsParticipant, as rclcpp_action and rcl_action serve them: the
/// send_goal, cancel_goal and get_result services and the feedback and status topics under
/// `<action>/_action/` (dds_action_wire.h has the names and encodings), with rcl's goal
/// bookkeeping: goals by UUID; ACCEPTED, EXECUTING, CANCELING, then SUCCEEDED, CANCELED or
/// ABORTED; the status array published on every change (transient local, so a late client sees
/// it); get_result requests answered when their goal ends, results kept for
/// ActionOptions::result_timeout (rcl in Humble: 15 minutes; Iron on: 10 s) and at most
/// max_finished_goals of them; cancel by id, by stamp, or all goals (zero id and zero stamp), with
/// rcl's return codes. Generic: goals, feedback and results are bodies (CDR messages) that the
/// action's codecs make and read.
///
/// Threads: as for ServiceServer (dds_services.h): one thread polls, and runs on_goal and
/// on_cancel; a GoalHandle may be used from any thread (the simulation thread steps the goal
/// and finishes it), its calls queue what goes out and wake the polling thread, which sends it.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "bridges/ros2/dds_action_wire.h"
#include "bridges/ros2/dds_participant.h"
#include "bridges/ros2/dds_services.h"

namespace rescuesim::ros2 {

namespace detail {
struct ActionState;
}

/// One goal of an ActionServer. Copyable; every call is thread-safe and returns false (doing
/// nothing) when the call does not fit the goal's state or the server has stopped.
class GoalHandle {
 public:
  GoalHandle() = default;
  const GoalId& id() const { return id_; }
  /// The goal: `<A>_Goal` as a CDR message.
  std::span<const std::uint8_t> goal() const;

  /// Accepts a new goal (answering its send_goal request with accepted = true and the acceptance
  /// stamp): EXECUTING, or ACCEPTED when `execute` is false (then execute() starts it).
  bool accept(bool execute = true);
  /// Rejects a new goal (accepted = false); the server forgets it.
  bool reject();
  /// ACCEPTED -> EXECUTING.
  bool execute();
  /// Publishes `feedback` (`<A>_Feedback` as a CDR message) for this goal; only while it runs.
  bool publish_feedback(std::span<const std::uint8_t> feedback);
  /// Ends the goal as SUCCEEDED, ABORTED or CANCELED with `result_response`: a whole
  /// `<A>_GetResult_Response_` as a CDR message, whose status (its first field) the server
  /// overwrites (dds_action_wire.h says why). Allowed from any state that has not ended (rcl
  /// allows fewer; a goal that cannot end would hang its clients).
  bool succeed(std::vector<std::uint8_t> result_response);
  bool abort(std::vector<std::uint8_t> result_response);
  bool canceled(std::vector<std::uint8_t> result_response);

  /// The goal's action_msgs/GoalStatus code (UNKNOWN before it is accepted and after it expired).
  std::int8_t status() const;
  /// True once a cancel request for it was accepted (CANCELING): the executor should stop it
  /// and call canceled().
  bool is_canceling() const { return status() == goal_status::kCanceling; }
  bool valid() const { return state_ != nullptr; }

 private:
  friend class ActionServer;
  bool finish(std::int8_t status, std::vector<std::uint8_t> result_response);

  std::shared_ptr<detail::ActionState> state_;
  GoalId id_{};
  std::shared_ptr<const std::vector<std::uint8_t>> goal_;
};

/// What an action does with its goals.
struct ActionCallbacks {
  /// A new goal: call accept() or reject() on it, now or later, from any thread. Required.
  std::function<void(GoalHandle)> on_goal;
  /// A cancel request for a goal that is ACCEPTED or EXECUTING: true accepts it (the goal turns
  /// CANCELING, and whoever executes it ends it, normally with canceled()), false refuses.
  /// Runs on the polling thread. Unset: every cancel is accepted.
  std::function<bool(GoalHandle)> on_cancel;
  /// A `<A>_GetResult_Response_` with a default result, the answer for goals the server does not
  /// know (status UNKNOWN, as rclcpp answers). Required (at least the status byte).
  std::vector<std::uint8_t> unknown_result_response;
};

struct ActionOptions {
  /// How long a finished goal's result is kept for get_result (wall clock).
  std::chrono::steady_clock::duration result_timeout = std::chrono::minutes(15);
  /// Most finished goals kept; the oldest are forgotten first.
  std::size_t max_finished_goals = 1000;
  /// The clock of goal stamps (ns; the acceptance stamps in send_goal replies and the status
  /// array, and cancel-by-stamp). Unset: the system clock. The bridge gives sim time.
  std::function<std::int64_t()> now_ns;
  /// Most feedback messages queued between two polls; the oldest are dropped beyond it.
  std::size_t max_queued_feedback = 100;
};

/// One action. See the file comment.
class ActionServer {
 public:
  /// Throws Error for missing callbacks or when the endpoints cannot be made.
  ActionServer(DdsParticipant& dds, ActionTopics topics, ActionCallbacks callbacks, ActionOptions options = {});
  ~ActionServer();
  ActionServer(const ActionServer&) = delete;
  ActionServer& operator=(const ActionServer&) = delete;

  /// Serves the three services, publishes the status and feedback that changed, forgets
  /// expired results. On the polling thread only.
  void poll(std::chrono::steady_clock::time_point now = std::chrono::steady_clock::now());
  /// When poll() must run again without new data (a reply waiting for its client, a result
  /// expiring); nullopt: nothing waits.
  std::optional<std::chrono::steady_clock::time_point> next_poll() const;

  const ActionTopics& topics() const { return topics_; }
  /// Its DDS readers and writers, for ros_discovery_info.
  std::vector<Guid> reader_guids() const;
  std::vector<Guid> writer_guids() const;
  /// Requests dropped as malformed on any of its services (short, not XCDR1, or a body that
  /// does not decode).
  std::uint64_t malformed() const;
  /// Feedback messages dropped because more than max_queued_feedback waited.
  std::uint64_t feedback_dropped() const;
  /// The status list as the status topic last carried or will carry it next, in acceptance order.
  std::vector<GoalStatus> status_list() const;

 private:
  void on_send_goal(const RequestHeader& header, std::span<const std::uint8_t> body, ReplyHandle reply);
  void on_cancel_goal(const RequestHeader& header, std::span<const std::uint8_t> body, ReplyHandle reply);
  void on_get_result(const RequestHeader& header, std::span<const std::uint8_t> body, ReplyHandle reply);
  void bad_body(const char* service, const std::string& why);
  void expire(std::chrono::steady_clock::time_point now);
  void publish();

  DdsParticipant& dds_;
  ActionTopics topics_;
  ActionCallbacks callbacks_;
  ActionOptions options_;
  std::shared_ptr<detail::ActionState> state_;
  int feedback_writer_ = -1, status_writer_ = -1;
  std::atomic<std::uint64_t> bad_bodies_{0};
  Throttle warning_;
  // last: destroyed first, so no handler runs on a half-destroyed server
  std::unique_ptr<ServiceServer> send_goal_, cancel_goal_, get_result_;
};

}  // namespace rescuesim::ros2
