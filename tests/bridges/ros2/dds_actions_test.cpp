// An action between two participants in this process, pinned to loopback, with
// simulation_interfaces/action/SimulateSteps's layouts written out by hand: a goal with feedback
// and a result asked for before it ends, a goal cancelled by id, goals cancelled all at once, a
// rejected goal, an unknown one, and the status array going through each transition.

#include "bridges/ros2/dds_actions.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <map>
#include <mutex>
#include <thread>

#include "bridges/common/cdr_stream.h"
#include "bridges/ros2/dds_action_client.h"
#include "bridges/ros2/service_registry.h"
#include "bridges/ros2/dds_loopback.h"
#include "bridges/ros2/registry_spinner.h"
#include "support/dds_domain.h"

namespace rescuesim::ros2 {
namespace {

using Bytes = std::vector<std::uint8_t>;
using namespace std::chrono_literals;

class DdsActionsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    testing::pin_cyclone_to_loopback();
  }
  int domain() const { return testing::leased_dds_domain(); }
};


// SimulateSteps: Goal {uint64 steps}; Feedback {uint64 completed_steps; uint64 remaining_steps};
// GetResult response {int8 status; simulation_interfaces/Result result {uint8 result; string error_message}}
Bytes goal(std::uint64_t steps) {
  Bytes out;
  cdr::Writer w(out, "SimulateSteps goal");
  w.value("steps", steps);
  return out;
}
Bytes feedback(std::uint64_t done, std::uint64_t left) {
  Bytes out;
  cdr::Writer w(out, "SimulateSteps feedback");
  w.value("completed_steps", done);
  w.value("remaining_steps", left);
  return out;
}
Bytes result(std::uint8_t code, const std::string& message) {
  Bytes out;
  cdr::Writer w(out, "SimulateSteps result");
  w.value<std::int8_t>("status", 0);  // the server writes it
  w.value("result.result", code);
  w.string("result.error_message", message);
  return out;
}
Bytes with_status(Bytes response, std::int8_t status) {
  response.at(4) = static_cast<std::uint8_t>(status);
  return response;
}

GoalId id_of(std::uint8_t b) {
  GoalId id;
  id.fill(b);
  return id;
}

/// The server side: a registry with /simulate_steps whose goals are accepted (steps > 0) or
/// rejected (0) at once, and kept for the test to drive; goal stamps come from a clock the test sets.
struct Server {
  explicit Server(DdsParticipant& dds, ActionOptions options = {}) : registry(dds, [this] { return clock_ns.load(); }) {
    ActionCallbacks callbacks;
    callbacks.on_goal = [this](GoalHandle h) {
      cdr::Reader in(h.goal(), "SimulateSteps goal");
      std::uint64_t steps = 0;
      in.value("steps", steps);
      if (steps == 0) {
        h.reject();
        return;
      }
      h.accept();
      std::lock_guard lock(mutex);
      goals[h.id()] = h;
    };
    callbacks.on_cancel = [this](GoalHandle h) { return !refuse_cancel.load() && h.valid(); };
    callbacks.unknown_result_response = result(0, "");
    action = &registry.add_action("/simulate_steps", "simulation_interfaces/action/SimulateSteps", callbacks, std::move(options));
  }
  GoalHandle goal(const GoalId& id) {
    std::lock_guard lock(mutex);
    return goals.at(id);
  }

  std::atomic<std::int64_t> clock_ns{0};
  std::atomic<bool> refuse_cancel{false};
  ServiceRegistry registry;
  ActionServer* action = nullptr;
  std::mutex mutex;
  std::map<GoalId, GoalHandle> goals;
};

/// Takes status arrays until the newest one equals `expected` (the topic keeps only the last).
bool status_becomes(ActionClient& client, const std::vector<GoalStatus>& expected) {
  const auto give_up = std::chrono::steady_clock::now() + 10s;
  std::vector<GoalStatus> last;
  while (std::chrono::steady_clock::now() < give_up) {
    for (auto& s : client.take_status()) last = std::move(s);
    if (last == expected) return true;
    client.wait_status(100ms);
  }
  return false;
}

GoalStatus st(const GoalId& id, std::int64_t stamp_ns, std::int8_t status) { return {{id, Stamp::from_ns(stamp_ns)}, status}; }

TEST_F(DdsActionsTest, GoalFeedbackResultCancelAndTheStatusArray) {
  DdsParticipant server_side(domain(), participant_user_data()), client_side(domain(), participant_user_data());
  Server server(server_side);
  testing::RegistrySpinner spinner(server.registry);
  ActionClient client(client_side, action_topics("/simulate_steps", "simulation_interfaces/action/SimulateSteps"));
  ASSERT_TRUE(client.wait_for_server(10s));
  std::string why;

  // goal A at stamp 5 s: accepted and executing
  const GoalId a = id_of(0xa1);
  server.clock_ns = 5'000'000'000;
  const auto sent = client.send_goal(a, goal(3), 10s, &why);
  ASSERT_TRUE(sent) << why;
  EXPECT_TRUE(sent->accepted);
  EXPECT_EQ(sent->stamp, (Stamp{5, 0}));
  EXPECT_TRUE(status_becomes(client, {st(a, 5'000'000'000, goal_status::kExecuting)}));

  // its result asked for before it ends, answered when it ends
  const auto result_seq = client.request_result(a, &why);
  ASSERT_TRUE(result_seq) << why;
  GoalHandle ha = server.goal(a);
  ASSERT_TRUE(ha.publish_feedback(feedback(1, 2)));
  ASSERT_TRUE(ha.publish_feedback(feedback(2, 1)));
  std::vector<FeedbackMessage> fb;
  const auto give_up = std::chrono::steady_clock::now() + 10s;
  while (fb.size() < 2 && std::chrono::steady_clock::now() < give_up) {
    client.wait_feedback(100ms);
    for (auto& f : client.take_feedback()) fb.push_back(std::move(f));
  }
  ASSERT_EQ(fb.size(), 2u);
  EXPECT_EQ(fb[0].id, a);
  EXPECT_EQ(fb[0].feedback, feedback(1, 2));
  EXPECT_EQ(fb[1].feedback, feedback(2, 1));
  ASSERT_TRUE(ha.succeed(result(1, "")));
  EXPECT_FALSE(ha.abort(result(4, "too late"))) << "an ended goal stays ended";
  EXPECT_FALSE(ha.publish_feedback(feedback(3, 0)));
  const auto done = client.wait_result(*result_seq, 10s, &why);
  ASSERT_TRUE(done) << why;
  EXPECT_EQ(*done, with_status(result(1, ""), goal_status::kSucceeded));
  EXPECT_TRUE(status_becomes(client, {st(a, 5'000'000'000, goal_status::kSucceeded)}));
  // and asked for after it ended, answered at once from what was kept
  const auto again = client.get_result(a, 10s, &why);
  ASSERT_TRUE(again) << why;
  EXPECT_EQ(*again, *done);

  // goal B at 6 s, cancelled by id: CANCELING, then CANCELED with its result
  const GoalId b = id_of(0xb2);
  server.clock_ns = 6'000'000'000;
  ASSERT_TRUE(client.send_goal(b, goal(100), 10s, &why)) << why;
  const auto cancel_b = client.cancel({b, {}}, 10s, &why);
  ASSERT_TRUE(cancel_b) << why;
  EXPECT_EQ(cancel_b->return_code, cancel_code::kNone);
  EXPECT_EQ(cancel_b->goals_canceling, (std::vector<GoalInfo>{{b, {6, 0}}}));
  GoalHandle hb = server.goal(b);
  EXPECT_TRUE(hb.is_canceling());
  EXPECT_TRUE(status_becomes(client, {st(a, 5'000'000'000, goal_status::kSucceeded), st(b, 6'000'000'000, goal_status::kCanceling)}));
  ASSERT_TRUE(hb.canceled(result(4, "cancelled")));
  const auto rb = client.get_result(b, 10s, &why);
  ASSERT_TRUE(rb) << why;
  EXPECT_EQ(*rb, with_status(result(4, "cancelled"), goal_status::kCanceled));

  // cancelling an ended goal, an unknown one
  const auto ended = client.cancel({a, {}}, 10s, &why);
  ASSERT_TRUE(ended) << why;
  EXPECT_EQ(ended->return_code, cancel_code::kGoalTerminated);
  EXPECT_TRUE(ended->goals_canceling.empty());
  const auto unknown = client.cancel({id_of(0xee), {}}, 10s, &why);
  ASSERT_TRUE(unknown) << why;
  EXPECT_EQ(unknown->return_code, cancel_code::kUnknownGoalId);

  // goals C (7 s) and D (8 s); a refused cancel of all, then an accepted one
  const GoalId c = id_of(0xc3), d = id_of(0xd4);
  server.clock_ns = 7'000'000'000;
  ASSERT_TRUE(client.send_goal(c, goal(100), 10s, &why)) << why;
  server.clock_ns = 8'000'000'000;
  ASSERT_TRUE(client.send_goal(d, goal(100), 10s, &why)) << why;
  server.refuse_cancel = true;
  const auto refused = client.cancel({}, 10s, &why);
  ASSERT_TRUE(refused) << why;
  EXPECT_EQ(refused->return_code, cancel_code::kRejected);
  EXPECT_EQ(server.goal(c).status(), goal_status::kExecuting);
  server.refuse_cancel = false;
  // by stamp: goals accepted at or before 7 s (C only; A and B have ended)
  const auto by_stamp = client.cancel({{}, {7, 0}}, 10s, &why);
  ASSERT_TRUE(by_stamp) << why;
  EXPECT_EQ(by_stamp->goals_canceling, (std::vector<GoalInfo>{{c, {7, 0}}}));
  // zero id and zero stamp: every goal still cancelable (D)
  const auto all = client.cancel({}, 10s, &why);
  ASSERT_TRUE(all) << why;
  EXPECT_EQ(all->return_code, cancel_code::kNone);
  EXPECT_EQ(all->goals_canceling, (std::vector<GoalInfo>{{d, {8, 0}}}));
  ASSERT_TRUE(server.goal(c).abort(result(4, "reset")));
  ASSERT_TRUE(server.goal(d).canceled(result(4, "cancelled")));
  EXPECT_TRUE(status_becomes(client, {st(a, 5'000'000'000, goal_status::kSucceeded), st(b, 6'000'000'000, goal_status::kCanceled),
                                      st(c, 7'000'000'000, goal_status::kAborted), st(d, 8'000'000'000, goal_status::kCanceled)}));

  // a rejected goal is not kept; an unknown goal's result is UNKNOWN with the default result
  const auto rejected = client.send_goal(id_of(0x0e), goal(0), 10s, &why);
  ASSERT_TRUE(rejected) << why;
  EXPECT_FALSE(rejected->accepted);
  EXPECT_EQ(rejected->stamp, Stamp{});
  const auto none = client.get_result(id_of(0x0e), 10s, &why);
  ASSERT_TRUE(none) << why;
  EXPECT_EQ(*none, with_status(result(0, ""), goal_status::kUnknown));
  // a goal id is used once
  const auto reused = client.send_goal(a, goal(3), 10s, &why);
  ASSERT_TRUE(reused) << why;
  EXPECT_FALSE(reused->accepted);
  EXPECT_EQ(server.action->malformed(), 0u);
}

TEST_F(DdsActionsTest, FinishedGoalsBeyondTheBoundAreForgottenOldestFirst) {
  DdsParticipant server_side(domain(), participant_user_data()), client_side(domain(), participant_user_data());
  ActionOptions options;
  options.max_finished_goals = 1;
  Server server(server_side, options);
  testing::RegistrySpinner spinner(server.registry);
  ActionClient client(client_side, action_topics("/simulate_steps", "simulation_interfaces/action/SimulateSteps"));
  ASSERT_TRUE(client.wait_for_server(10s));
  std::string why;
  const GoalId first = id_of(1), second = id_of(2);
  ASSERT_TRUE(client.send_goal(first, goal(1), 10s, &why)) << why;
  ASSERT_TRUE(server.goal(first).succeed(result(1, "")));
  ASSERT_TRUE(client.send_goal(second, goal(1), 10s, &why)) << why;
  ASSERT_TRUE(server.goal(second).succeed(result(1, "")));
  // once the second has ended, only it is kept
  EXPECT_TRUE(status_becomes(client, {st(second, 0, goal_status::kSucceeded)}));
  const auto r1 = client.get_result(first, 10s, &why);
  ASSERT_TRUE(r1) << why;
  EXPECT_EQ(result_status(*r1), goal_status::kUnknown);
  const auto r2 = client.get_result(second, 10s, &why);
  ASSERT_TRUE(r2) << why;
  EXPECT_EQ(result_status(*r2), goal_status::kSucceeded);
}

TEST_F(DdsActionsTest, MalformedGoalRequestsAreCountedAndUnanswered) {
  DdsParticipant server_side(domain(), participant_user_data()), client_side(domain(), participant_user_data());
  Server server(server_side);
  testing::RegistrySpinner spinner(server.registry);
  const ActionTopics topics = action_topics("/simulate_steps", "simulation_interfaces/action/SimulateSteps");
  ServiceClient send_goal(client_side, topics.send_goal);
  ASSERT_TRUE(send_goal.wait_for_server(10s));
  std::string why;
  // a request header and 15 bytes: too short for the goal's UUID
  EXPECT_FALSE(send_goal.call(Bytes{0x00, 0x01, 0x00, 0x00, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15}, 300ms, &why));
  // the next, well-formed one is answered (so the first was seen, and dropped)
  const auto ok = send_goal.call(encode_send_goal_request(id_of(7), goal(2)), 10s, &why);
  ASSERT_TRUE(ok) << why;
  EXPECT_TRUE(decode_send_goal_response(*ok).accepted);
  EXPECT_EQ(server.action->malformed(), 1u);
  EXPECT_EQ(server.registry.malformed(), 1u);
}

}  // namespace
}  // namespace rescuesim::ros2
