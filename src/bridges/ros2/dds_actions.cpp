#include "bridges/ros2/dds_actions.h"

#include <algorithm>
#include <deque>
#include <exception>
#include <limits>
#include <map>
#include <mutex>
#include <utility>

#include "core/error.h"
#include "core/log.h"

namespace rescuesim::ros2 {

namespace detail {

/// One goal the server knows: accepted ones, and new ones not yet accepted or rejected.
struct ActionGoal {
  GoalInfo info;
  std::int8_t status = goal_status::kUnknown;
  bool decided = false;                          ///< accepted (rejected goals are forgotten)
  ReplyHandle goal_reply;                        ///< the send_goal request, until decided
  std::vector<ReplyHandle> result_waiters;       ///< get_result requests before the goal ended
  std::vector<std::uint8_t> result;              ///< the GetResult response, once ended
  std::uint64_t order = 0;                       ///< arrival order, the status list's order
  std::chrono::steady_clock::time_point ended;   ///< when it ended, for result_timeout
  std::shared_ptr<const std::vector<std::uint8_t>> goal;
};

/// What an ActionServer shares with its GoalHandles, under one mutex.
struct ActionState {
  std::mutex mutex;
  DdsParticipant* dds = nullptr;  ///< to wake the polling thread; null once the server is gone
  std::map<GoalId, ActionGoal> goals;
  std::uint64_t next_order = 0;
  bool status_dirty = false;
  std::deque<std::vector<std::uint8_t>> feedback;  ///< FeedbackMessage bodies to publish
  std::size_t max_feedback = 100;
  std::uint64_t feedback_dropped = 0;
  std::function<std::int64_t()> now_ns;

  void wake() {
    if (dds) dds->wake();
  }
  /// The status list in arrival order (accepted goals only).
  std::vector<GoalStatus> status_list() const {
    std::vector<std::pair<std::uint64_t, GoalStatus>> list;
    for (const auto& [id, g] : goals) {
      if (g.decided) list.push_back({g.order, {g.info, g.status}});
    }
    std::sort(list.begin(), list.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<GoalStatus> out;
    for (auto& [order, s] : list) out.push_back(s);
    return out;
  }
};

}  // namespace detail

namespace {

bool cancelable(std::int8_t s) { return s == goal_status::kAccepted || s == goal_status::kExecuting; }

std::int64_t system_now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
}

}  // namespace

std::span<const std::uint8_t> GoalHandle::goal() const {
  if (!goal_) return {};
  return *goal_;
}

bool GoalHandle::accept(bool execute) {
  if (!state_) return false;
  ReplyHandle reply;
  Stamp stamp;
  {
    std::lock_guard lock(state_->mutex);
    const auto it = state_->goals.find(id_);
    if (state_->dds == nullptr || it == state_->goals.end() || it->second.decided) return false;
    detail::ActionGoal& g = it->second;
    g.decided = true;
    g.status = execute ? goal_status::kExecuting : goal_status::kAccepted;
    g.info.stamp = stamp = Stamp::from_ns(state_->now_ns());
    reply = std::exchange(g.goal_reply, ReplyHandle{});
    state_->status_dirty = true;
    state_->wake();
  }
  reply.send(encode_send_goal_response({true, stamp}));
  return true;
}

bool GoalHandle::reject() {
  if (!state_) return false;
  ReplyHandle reply;
  {
    std::lock_guard lock(state_->mutex);
    const auto it = state_->goals.find(id_);
    if (state_->dds == nullptr || it == state_->goals.end() || it->second.decided) return false;
    reply = std::move(it->second.goal_reply);
    state_->goals.erase(it);
  }
  // rclcpp leaves the stamp of a rejected goal at zero
  reply.send(encode_send_goal_response({false, {}}));
  return true;
}

bool GoalHandle::execute() {
  if (!state_) return false;
  std::lock_guard lock(state_->mutex);
  const auto it = state_->goals.find(id_);
  if (state_->dds == nullptr || it == state_->goals.end() || !it->second.decided || it->second.status != goal_status::kAccepted) {
    return false;
  }
  it->second.status = goal_status::kExecuting;
  state_->status_dirty = true;
  state_->wake();
  return true;
}

bool GoalHandle::publish_feedback(std::span<const std::uint8_t> feedback) {
  if (!state_) return false;
  std::vector<std::uint8_t> message;
  try {
    message = encode_feedback_message(id_, feedback);
  } catch (const Error& e) {
    log::warn("ROS 2 bridge: action feedback not sent: {}", e.message());
    return false;
  }
  std::lock_guard lock(state_->mutex);
  const auto it = state_->goals.find(id_);
  if (state_->dds == nullptr || it == state_->goals.end() || !it->second.decided || goal_status::terminal(it->second.status)) {
    return false;
  }
  state_->feedback.push_back(std::move(message));
  if (state_->feedback.size() > state_->max_feedback) {
    state_->feedback.pop_front();
    ++state_->feedback_dropped;
  }
  state_->wake();
  return true;
}

bool GoalHandle::succeed(std::vector<std::uint8_t> result_response) { return finish(goal_status::kSucceeded, std::move(result_response)); }
bool GoalHandle::abort(std::vector<std::uint8_t> result_response) { return finish(goal_status::kAborted, std::move(result_response)); }
bool GoalHandle::canceled(std::vector<std::uint8_t> result_response) { return finish(goal_status::kCanceled, std::move(result_response)); }

bool GoalHandle::finish(std::int8_t status, std::vector<std::uint8_t> result_response) {
  if (!state_) return false;
  try {
    set_result_status(result_response, status);
  } catch (const Error& e) {
    log::warn("ROS 2 bridge: action result not taken: {}", e.message());
    return false;
  }
  std::vector<ReplyHandle> waiters;
  {
    std::lock_guard lock(state_->mutex);
    const auto it = state_->goals.find(id_);
    if (state_->dds == nullptr || it == state_->goals.end() || !it->second.decided || goal_status::terminal(it->second.status)) {
      return false;
    }
    detail::ActionGoal& g = it->second;
    g.status = status;
    g.result = result_response;
    g.ended = std::chrono::steady_clock::now();
    waiters = std::move(g.result_waiters);
    g.result_waiters.clear();
    state_->status_dirty = true;
    state_->wake();
  }
  // the get_result requests that came before the end get their answer now
  for (const ReplyHandle& w : waiters) w.send(result_response);
  return true;
}

std::int8_t GoalHandle::status() const {
  if (!state_) return goal_status::kUnknown;
  std::lock_guard lock(state_->mutex);
  const auto it = state_->goals.find(id_);
  return it == state_->goals.end() || !it->second.decided ? goal_status::kUnknown : it->second.status;
}

ActionServer::ActionServer(DdsParticipant& dds, ActionTopics topics, ActionCallbacks callbacks, ActionOptions options)
    : dds_(dds), topics_(std::move(topics)), callbacks_(std::move(callbacks)), options_(std::move(options)) {
  if (!callbacks_.on_goal) throw Error("action " + topics_.name + ": on_goal is required");
  try {
    set_result_status(callbacks_.unknown_result_response, goal_status::kUnknown);
  } catch (const Error& e) {
    throw Error("action " + topics_.name + ": unknown_result_response: " + e.message());
  }
  state_ = std::make_shared<detail::ActionState>();
  state_->now_ns = options_.now_ns ? options_.now_ns : system_now_ns;
  state_->max_feedback = std::max<std::size_t>(1, options_.max_queued_feedback);
  feedback_writer_ = dds_.create_raw_writer(topics_.feedback_topic, topics_.feedback_type, action_feedback_qos());
  status_writer_ = dds_.create_raw_writer(topics_.status_topic, topics_.status_type, action_status_qos());
  send_goal_ = std::make_unique<ServiceServer>(dds_, topics_.send_goal, [this](const RequestHeader& h, auto body, ReplyHandle r) {
    on_send_goal(h, body, std::move(r));
  });
  cancel_goal_ = std::make_unique<ServiceServer>(dds_, topics_.cancel_goal, [this](const RequestHeader& h, auto body, ReplyHandle r) {
    on_cancel_goal(h, body, std::move(r));
  });
  get_result_ = std::make_unique<ServiceServer>(dds_, topics_.get_result, [this](const RequestHeader& h, auto body, ReplyHandle r) {
    on_get_result(h, body, std::move(r));
  });
  std::lock_guard lock(state_->mutex);
  state_->dds = &dds_;
}

ActionServer::~ActionServer() {
  // handles held elsewhere (the simulation thread's) find the server gone
  std::lock_guard lock(state_->mutex);
  state_->dds = nullptr;
  state_->goals.clear();
  state_->feedback.clear();
}

std::vector<Guid> ActionServer::reader_guids() const {
  return {send_goal_->request_reader_guid(), cancel_goal_->request_reader_guid(), get_result_->request_reader_guid()};
}

std::vector<Guid> ActionServer::writer_guids() const {
  return {send_goal_->reply_writer_guid(), cancel_goal_->reply_writer_guid(), get_result_->reply_writer_guid(),
          dds_.writer_guid(feedback_writer_), dds_.writer_guid(status_writer_)};
}

std::uint64_t ActionServer::malformed() const {
  return send_goal_->malformed() + cancel_goal_->malformed() + get_result_->malformed() + bad_bodies_.load();
}

std::uint64_t ActionServer::feedback_dropped() const {
  std::lock_guard lock(state_->mutex);
  return state_->feedback_dropped;
}

std::vector<GoalStatus> ActionServer::status_list() const {
  std::lock_guard lock(state_->mutex);
  return state_->status_list();
}

void ActionServer::bad_body(const char* service, const std::string& why) {
  ++bad_bodies_;
  std::uint64_t held = 0;
  if (warning_.allow(&held)) {
    log::warn("ROS 2 bridge: action {}: dropped a malformed {} request: {} ({} more problems held back)", topics_.name, service, why,
              held);
  }
}

void ActionServer::on_send_goal(const RequestHeader&, std::span<const std::uint8_t> body, ReplyHandle reply) {
  SendGoalRequest request;
  try {
    request = decode_send_goal_request(body);
  } catch (const Error& e) {
    return bad_body("send_goal", e.message());
  }
  auto goal = std::make_shared<const std::vector<std::uint8_t>>(std::move(request.goal));
  bool known = false;
  {
    std::lock_guard lock(state_->mutex);
    known = state_->goals.contains(request.id);
    if (!known) {
      detail::ActionGoal g;
      g.info.id = request.id;
      g.goal_reply = reply;
      g.order = state_->next_order++;
      g.goal = goal;
      state_->goals.emplace(request.id, std::move(g));
    }
  }
  if (known) {
    // a goal id is used once (rclpy rejects a repeated one too)
    log::warn("ROS 2 bridge: action {}: rejected a goal whose id is in use", topics_.name);
    reply.send(encode_send_goal_response({false, {}}));
    return;
  }
  GoalHandle handle;
  handle.state_ = state_;
  handle.id_ = request.id;
  handle.goal_ = std::move(goal);
  try {
    callbacks_.on_goal(handle);
  } catch (const std::exception& e) {
    log::warn("ROS 2 bridge: action {}: on_goal failed: {} (goal rejected)", topics_.name, e.what());
    handle.reject();
  }
}

void ActionServer::on_cancel_goal(const RequestHeader&, std::span<const std::uint8_t> body, ReplyHandle reply) {
  GoalInfo request;
  try {
    request = decode_cancel_request(body);
  } catch (const Error& e) {
    return bad_body("cancel_goal", e.message());
  }
  // rcl_action_process_cancel_request: which goals; then, as rclcpp, ask on_cancel for each
  const bool by_id = request.id != GoalId{};
  const std::int64_t by_stamp = request.stamp.ns();
  CancelResponse response;
  std::vector<GoalHandle> candidates;
  const auto handle_of = [&](const detail::ActionGoal& g) {
    GoalHandle h;
    h.state_ = state_;
    h.id_ = g.info.id;
    h.goal_ = g.goal;
    return h;
  };
  {
    std::lock_guard lock(state_->mutex);
    if (by_id && by_stamp == 0) {
      // exactly one goal
      response.return_code = cancel_code::kUnknownGoalId;
      const auto it = state_->goals.find(request.id);
      if (it != state_->goals.end() && it->second.decided) {
        if (cancelable(it->second.status)) {
          candidates.push_back(handle_of(it->second));
          response.return_code = cancel_code::kNone;
        } else {
          response.return_code = cancel_code::kGoalTerminated;  // rcl's word for "not cancelable"
        }
      }
    } else {
      // every goal accepted at or before the stamp (zero id and zero stamp: all), and the one named
      response.return_code = cancel_code::kNone;
      const std::int64_t limit = !by_id && by_stamp == 0 ? std::numeric_limits<std::int64_t>::max() : by_stamp;
      for (const GoalStatus& s : state_->status_list()) {
        if (cancelable(s.status) && (s.info.stamp.ns() <= limit || (by_id && s.info.id == request.id))) {
          candidates.push_back(handle_of(state_->goals.at(s.info.id)));
        }
      }
    }
  }
  for (GoalHandle& h : candidates) {
    bool accepted = true;
    if (callbacks_.on_cancel) {
      try {
        accepted = callbacks_.on_cancel(h);
      } catch (const std::exception& e) {
        log::warn("ROS 2 bridge: action {}: on_cancel failed: {} (cancel refused)", topics_.name, e.what());
        accepted = false;
      }
    }
    if (!accepted) continue;
    std::lock_guard lock(state_->mutex);
    const auto it = state_->goals.find(h.id());
    if (it == state_->goals.end()) continue;
    if (cancelable(it->second.status)) {
      it->second.status = goal_status::kCanceling;
      state_->status_dirty = true;
    } else if (it->second.status != goal_status::kCanceled) {
      continue;  // ended otherwise meanwhile
    }
    response.goals_canceling.push_back(it->second.info);
  }
  // rclcpp: when every goal asked about refuses, the request as a whole is rejected
  if (!candidates.empty() && response.goals_canceling.empty()) response.return_code = cancel_code::kRejected;
  reply.send(encode_cancel_response(response));
}

void ActionServer::on_get_result(const RequestHeader&, std::span<const std::uint8_t> body, ReplyHandle reply) {
  GoalId id;
  try {
    id = decode_result_request(body);
  } catch (const Error& e) {
    return bad_body("get_result", e.message());
  }
  std::vector<std::uint8_t> answer;
  {
    std::lock_guard lock(state_->mutex);
    const auto it = state_->goals.find(id);
    if (it == state_->goals.end() || !it->second.decided) {
      answer = callbacks_.unknown_result_response;  // status UNKNOWN, as rclcpp answers
    } else if (goal_status::terminal(it->second.status)) {
      answer = it->second.result;
    } else {
      it->second.result_waiters.push_back(std::move(reply));  // answered when the goal ends
      return;
    }
  }
  reply.send(answer);
}

void ActionServer::expire(std::chrono::steady_clock::time_point now) {
  std::lock_guard lock(state_->mutex);
  std::vector<std::pair<std::chrono::steady_clock::time_point, GoalId>> finished;
  for (auto it = state_->goals.begin(); it != state_->goals.end();) {
    if (it->second.decided && goal_status::terminal(it->second.status)) {
      if (now - it->second.ended >= options_.result_timeout) {
        it = state_->goals.erase(it);
        state_->status_dirty = true;
        continue;
      }
      finished.push_back({it->second.ended, it->first});
    }
    ++it;
  }
  if (finished.size() <= options_.max_finished_goals) return;
  std::sort(finished.begin(), finished.end());
  for (std::size_t i = 0; i < finished.size() - options_.max_finished_goals; ++i) state_->goals.erase(finished[i].second);
  state_->status_dirty = true;
}

void ActionServer::publish() {
  std::vector<std::uint8_t> status;
  std::deque<std::vector<std::uint8_t>> feedback;
  {
    std::lock_guard lock(state_->mutex);
    if (state_->status_dirty) {
      state_->status_dirty = false;
      status = encode_status_array(state_->status_list());
    }
    feedback.swap(state_->feedback);
  }
  std::string error;
  if (!status.empty() && !dds_.write(status_writer_, status, &error)) {
    log::warn("ROS 2 bridge: action {}: cannot publish the status: {}", topics_.name, error);
  }
  for (const auto& f : feedback) {
    if (!dds_.write(feedback_writer_, f, &error)) log::warn("ROS 2 bridge: action {}: cannot publish feedback: {}", topics_.name, error);
  }
}

void ActionServer::poll(std::chrono::steady_clock::time_point now) {
  send_goal_->poll(now);
  cancel_goal_->poll(now);
  get_result_->poll(now);
  expire(now);
  publish();
}

std::optional<std::chrono::steady_clock::time_point> ActionServer::next_poll() const {
  std::optional<std::chrono::steady_clock::time_point> next;
  const auto earliest = [&](std::optional<std::chrono::steady_clock::time_point> t) {
    if (t && (!next || *t < *next)) next = t;
  };
  earliest(send_goal_->next_poll());
  earliest(cancel_goal_->next_poll());
  earliest(get_result_->next_poll());
  std::lock_guard lock(state_->mutex);
  if (state_->status_dirty || !state_->feedback.empty()) earliest(std::chrono::steady_clock::now());
  for (const auto& [id, g] : state_->goals) {
    if (g.decided && goal_status::terminal(g.status)) earliest(g.ended + options_.result_timeout);
  }
  return next;
}

}  // namespace rescuesim::ros2
