// The action_msgs encodings the transport writes itself, worked out by hand from the IDL
// (UUID = uint8[16], Time = int32 sec + uint32 nanosec, alignment counted after the
// encapsulation header), and the names rcl_action gives an action's services and topics.

#include "bridges/ros2/dds_action_wire.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace rescuesim::ros2 {
namespace {

using Bytes = std::vector<std::uint8_t>;

GoalId id_of(std::uint8_t b) {
  GoalId id;
  id.fill(b);
  return id;
}

Bytes cat(std::initializer_list<Bytes> parts) {
  Bytes out;
  for (const Bytes& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

const Bytes kLe = {0x00, 0x01, 0x00, 0x00};

TEST(ActionWire, NamesAndTypesFollowRclAction) {
  const ActionTopics t = action_topics("/simulate_steps", "simulation_interfaces/action/SimulateSteps");
  EXPECT_EQ(t.send_goal.request_topic, "rq/simulate_steps/_action/send_goalRequest");
  EXPECT_EQ(t.send_goal.reply_topic, "rr/simulate_steps/_action/send_goalReply");
  EXPECT_EQ(t.send_goal.request_type, "simulation_interfaces::action::dds_::SimulateSteps_SendGoal_Request_");
  EXPECT_EQ(t.send_goal.reply_type, "simulation_interfaces::action::dds_::SimulateSteps_SendGoal_Response_");
  EXPECT_EQ(t.cancel_goal.request_topic, "rq/simulate_steps/_action/cancel_goalRequest");
  EXPECT_EQ(t.cancel_goal.request_type, "action_msgs::srv::dds_::CancelGoal_Request_");
  EXPECT_EQ(t.cancel_goal.reply_type, "action_msgs::srv::dds_::CancelGoal_Response_");
  EXPECT_EQ(t.get_result.name, "/simulate_steps/_action/get_result");
  EXPECT_EQ(t.get_result.request_type, "simulation_interfaces::action::dds_::SimulateSteps_GetResult_Request_");
  EXPECT_EQ(t.get_result.reply_type, "simulation_interfaces::action::dds_::SimulateSteps_GetResult_Response_");
  EXPECT_EQ(t.feedback_topic, "rt/simulate_steps/_action/feedback");
  EXPECT_EQ(t.feedback_type, "simulation_interfaces::action::dds_::SimulateSteps_FeedbackMessage_");
  EXPECT_EQ(t.status_topic, "rt/simulate_steps/_action/status");
  EXPECT_EQ(t.status_type, "action_msgs::msg::dds_::GoalStatusArray_");
  EXPECT_EQ(action_status_qos(), (EndpointQos{Reliability::reliable, Durability::transient_local, 1}));
  EXPECT_THROW(action_topics("/a", "pkg/srv/A"), Error);
}

TEST(ActionWire, StatusArrayPadsBeforeEachStampButNotBeforeEachUuid) {
  const std::vector<GoalStatus> list = {{{id_of(0x11), {3, 500}}, goal_status::kExecuting},
                                        {{id_of(0x22), {4, 0}}, goal_status::kSucceeded}};
  // count at 0; A: uuid 4..19, sec 20, nanosec 24, status 28; B: uuid 29..44, padding 45..47,
  // sec 48, nanosec 52, status 56
  const Bytes expected = cat({kLe, {0x02, 0, 0, 0}, Bytes(16, 0x11), {0x03, 0, 0, 0}, {0xf4, 0x01, 0, 0}, {0x02},
                              Bytes(16, 0x22), {0, 0, 0}, {0x04, 0, 0, 0}, {0, 0, 0, 0}, {0x04}});
  EXPECT_EQ(encode_status_array(list), expected);
  EXPECT_EQ(decode_status_array(expected), list);
  EXPECT_TRUE(decode_status_array(encode_status_array({})).empty());
}

TEST(ActionWire, CancelRequestAndResponse) {
  const GoalInfo all{};  // zero id and zero stamp: every goal
  EXPECT_EQ(encode_cancel_request(all), cat({kLe, Bytes(24, 0)}));
  const GoalInfo one{id_of(0x33), {1, 2}};
  const Bytes request = cat({kLe, Bytes(16, 0x33), {1, 0, 0, 0}, {2, 0, 0, 0}});
  EXPECT_EQ(encode_cancel_request(one), request);
  EXPECT_EQ(decode_cancel_request(request), one);
  // return_code at 0, padding, count at 4, the GoalInfo from 8 (uuid 8..23, sec 24, nanosec 28)
  const CancelResponse r{cancel_code::kNone, {one}};
  const Bytes response = cat({kLe, {0, 0, 0, 0}, {1, 0, 0, 0}, Bytes(16, 0x33), {1, 0, 0, 0}, {2, 0, 0, 0}});
  EXPECT_EQ(encode_cancel_response(r), response);
  const CancelResponse back = decode_cancel_response(response);
  EXPECT_EQ(back.return_code, cancel_code::kNone);
  EXPECT_EQ(back.goals_canceling, r.goals_canceling);
  // a count the bytes cannot hold is refused, not allocated
  EXPECT_THROW(decode_cancel_response(cat({kLe, {0, 0, 0, 0}, {0xff, 0xff, 0xff, 0x7f}})), Error);
  EXPECT_THROW(decode_cancel_request(cat({kLe, Bytes(20, 0)})), Error);  // cut in the stamp
}

TEST(ActionWire, SendGoalSplitsTheUuidFromAStandaloneGoal) {
  // SimulateSteps_Goal {uint64 steps = 7}: on its own, the steps at 0
  const Bytes goal = cat({kLe, {7, 0, 0, 0, 0, 0, 0, 0}});
  const Bytes request = cat({kLe, Bytes(16, 0x44), {7, 0, 0, 0, 0, 0, 0, 0}});  // steps at 16: aligned alike
  EXPECT_EQ(encode_send_goal_request(id_of(0x44), goal), request);
  const SendGoalRequest r = decode_send_goal_request(request);
  EXPECT_EQ(r.id, id_of(0x44));
  EXPECT_EQ(r.goal, goal);
  EXPECT_THROW(decode_send_goal_request(cat({kLe, Bytes(15, 0)})), Error);
  // bool accepted at 0, padding, sec at 4, nanosec at 8
  const Bytes response = cat({kLe, {1, 0, 0, 0}, {7, 0, 0, 0}, {9, 0, 0, 0}});
  EXPECT_EQ(encode_send_goal_response({true, {7, 9}}), response);
  const SendGoalResponse back = decode_send_goal_response(response);
  EXPECT_TRUE(back.accepted);
  EXPECT_EQ(back.stamp, (Stamp{7, 9}));
}

TEST(ActionWire, ResultStatusIsTheFirstByteOfTheResponse) {
  // SimulateSteps_GetResult_Response {int8 status; Result result {uint8 result; string error_message}}:
  // status 0, result 1, padding 2..3, length at 4
  Bytes response = cat({kLe, {0, 1, 0, 0}, {1, 0, 0, 0}, {0}});
  set_result_status(response, goal_status::kSucceeded);
  EXPECT_EQ(response, cat({kLe, {4, 1, 0, 0}, {1, 0, 0, 0}, {0}}));
  EXPECT_EQ(result_status(response), goal_status::kSucceeded);
  Bytes empty = kLe;
  EXPECT_THROW(set_result_status(empty, 1), Error);
  EXPECT_EQ(encode_result_request(id_of(5)), cat({kLe, Bytes(16, 5)}));
  EXPECT_EQ(decode_result_request(cat({kLe, Bytes(16, 5)})), id_of(5));
}

TEST(ActionWire, FeedbackMessageIsTheUuidThenTheFeedback) {
  // SimulateSteps_Feedback {uint64 completed_steps = 3; uint64 remaining_steps = 4}
  const Bytes feedback = cat({kLe, {3, 0, 0, 0, 0, 0, 0, 0}, {4, 0, 0, 0, 0, 0, 0, 0}});
  const Bytes message = encode_feedback_message(id_of(9), feedback);
  EXPECT_EQ(message, cat({kLe, Bytes(16, 9), {3, 0, 0, 0, 0, 0, 0, 0}, {4, 0, 0, 0, 0, 0, 0, 0}}));
  const FeedbackMessage back = decode_feedback_message(message);
  EXPECT_EQ(back.id, id_of(9));
  EXPECT_EQ(back.feedback, feedback);
}

TEST(ActionWire, StampsSplitNanosecondsTheRosWay) {
  EXPECT_EQ(Stamp::from_ns(1'500'000'000), (Stamp{1, 500'000'000}));
  EXPECT_EQ(Stamp::from_ns(-1), (Stamp{-1, 999'999'999}));
  EXPECT_EQ((Stamp{2, 5}).ns(), 2'000'000'005);
}

}  // namespace
}  // namespace rescuesim::ros2
