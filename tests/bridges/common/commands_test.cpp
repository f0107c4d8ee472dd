// Commands from the network: refused when malformed or non-finite, counted, warned about by
// topic and value (throttled), and otherwise applied at the next step boundary.

#include "bridges/common/commands.h"

#include <gtest/gtest.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <limits>

#include "robots/rescue_robot.h"
#include "sim/simulation.h"
#include "sim/slider_robot.h"
#include "support/log_capture.h"
#include "support/rig.h"

namespace rescuesim {
namespace {

class CommandGateTest : public ::testing::Test {
 protected:
  CommandGateTest() : sim_(compile_world(testing::room_spec(), builtin_models())), gate_(sim_, "ROS 1") {}
  Simulation sim_;
  CommandGate gate_;
};

TEST_F(CommandGateTest, AFiniteTwistReachesTheRobotAtTheNextStep) {
  msg::Twist t;
  t.linear.x() = 0.3;
  t.angular.z() = -0.5;
  EXPECT_TRUE(gate_.velocity(RobotIndex(0), "/cmd_vel", t));
  EXPECT_EQ(gate_.received(), 1u);
  EXPECT_EQ(gate_.rejected(), 0u);
  sim_.step();
  EXPECT_DOUBLE_EQ(sim_.state().robots[0].cmd_linear.x(), 0.3);
  EXPECT_DOUBLE_EQ(sim_.state().robots[0].cmd_angular.z(), -0.5);
}

TEST_F(CommandGateTest, NonFiniteTwistsAreRefusedWithTheTopicAndTheValue) {
  testing::LogCapture log(100);
  msg::Twist t;
  t.linear.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(gate_.velocity(RobotIndex(0), "/cmd_vel", t));
  t.linear.x() = 0;
  t.angular.y() = std::numeric_limits<double>::infinity();  // even a component the drive ignores
  EXPECT_FALSE(gate_.velocity(RobotIndex(0), "/cmd_vel", t));
  EXPECT_EQ(gate_.rejected(), 2u);
  EXPECT_EQ(gate_.received(), 0u);
  sim_.step();
  EXPECT_DOUBLE_EQ(sim_.state().robots[0].cmd_linear.x(), 0.0);
  // the first warning names topic, field and value; the second is held back (throttled)
  const std::string text = log.text();
  EXPECT_NE(text.find("rejected a command on /cmd_vel: linear.x is nan"), std::string::npos) << text;
  EXPECT_EQ(text.find("angular.y"), std::string::npos) << text;
}

TEST_F(CommandGateTest, SpeedsBeyondTheLimitsAreAcceptedWithAClampWarning) {
  testing::LogCapture log(100);
  msg::Twist t;
  t.linear.x() = 5.0;
  t.angular.z() = -9.0;
  EXPECT_TRUE(gate_.velocity(RobotIndex(0), "/cmd_vel", t));
  const std::string text = log.text();
  EXPECT_NE(text.find("/cmd_vel linear.x = 5 m/s is beyond the robot's max_linear: clamped to 1 m/s"), std::string::npos) << text;
  EXPECT_NE(text.find("/cmd_vel angular.z = -9 rad/s is beyond the robot's max_angular: clamped to -2 rad/s"), std::string::npos) << text;
}

TEST_F(CommandGateTest, HeadCommandsNeedOnePositionPerHeadJoint) {
  testing::LogCapture log(100);
  const std::size_t n = sim_.world().robots[0].spec.head_joints.size();
  ASSERT_EQ(n, 4u);
  EXPECT_FALSE(gate_.head(RobotIndex(0), "/head/command", {0.1}));
  EXPECT_NE(log.text().find("rejected a command on /head/command: 1 positions, expected 4 (rad, in the order mast_yaw"), std::string::npos)
      << log.text();
  EXPECT_FALSE(gate_.head(RobotIndex(0), "/head/command", {0.1, NAN, 0, 0}));
  EXPECT_TRUE(gate_.head(RobotIndex(0), "/head/command", {0.1, 0.2, -0.3, 0.4}));
  EXPECT_EQ(gate_.rejected(), 2u);
  EXPECT_EQ(gate_.received(), 1u);
  sim_.step();
  EXPECT_EQ(sim_.state().robots[0].head_target, (std::vector<double>{0.1, 0.2, -0.3, 0.4}));
}

TEST_F(CommandGateTest, HeadTargetsBeyondAJointsLimitsAreClampedWithAWarning) {
  testing::LogCapture log(100);
  EXPECT_TRUE(gate_.head(RobotIndex(0), "/head/command", {0, 0, 0, 9.0}));
  EXPECT_NE(log.text().find("/head/command data[3] (head_tilt) = 9 rad (516 deg) is beyond the joint's limits: clamped to"),
            std::string::npos)
      << log.text();
}

TEST_F(CommandGateTest, MalformedBytesAreCountedAsRejected) {
  testing::LogCapture log(100);
  gate_.malformed("/cmd_vel", "geometry_msgs/Twist: angular.z: needs 8 bytes, 3 left");
  EXPECT_EQ(gate_.rejected(), 1u);
  EXPECT_NE(log.text().find("rejected a command on /cmd_vel: malformed message: geometry_msgs/Twist"), std::string::npos) << log.text();
}

TEST(CommandGateJoints, RefusalsSayWhichJointAndWhyAndClampsAreReported) {
  Simulation sim(testing::slider_world());
  CommandGate gate(sim, "ROS 1");
  testing::LogCapture log(100);
  msg::JointState wheel;
  wheel.name = {"wheel"};
  wheel.velocity = {1.0};
  EXPECT_FALSE(gate.joints(RobotIndex(0), "/joint_command", wheel));
  EXPECT_NE(log.text().find("ROS 1: rejected a command on /joint_command: 'wheel' is a drive wheel (use cmd_vel): not commandable"),
            std::string::npos)
      << log.text();
  msg::JointState lift;
  lift.name = {"lift"};
  lift.position = {0.5};
  EXPECT_TRUE(gate.joints(RobotIndex(0), "/joint_command", lift));
  EXPECT_NE(log.text().find("/joint_command position of lift = 0.5 is beyond the joint's limits [-0.1, 0.2]: clamped to 0.2"),
            std::string::npos)
      << log.text();
  EXPECT_EQ(gate.received(), 1u);
  EXPECT_EQ(gate.rejected(), 1u);
  sim.step();
  EXPECT_EQ(sim.state().robots[0].joint_target[0], 0.2);
}

TEST(CommandGateFlippers, FlipperPositionsBecomeJointTargetsAndAWrongCountIsRefused) {
  WorldSpec spec = testing::room_spec();
  spec.robots[0].model = "tracked_robot";
  Simulation sim(compile_world(spec, builtin_models()));
  CommandGate gate(sim, "ROS 2");
  testing::LogCapture log(100);
  EXPECT_FALSE(gate.flippers(RobotIndex(0), "/flippers/command", {0.3}));
  EXPECT_NE(log.text().find("/flippers/command: 1 positions, expected 2 (rad, in the order left_flipper_joint, right_flipper_joint)"),
            std::string::npos)
      << log.text();
  EXPECT_FALSE(gate.flippers(RobotIndex(0), "/flippers/command", {0.3, std::nan("")}));
  EXPECT_TRUE(gate.flippers(RobotIndex(0), "/flippers/command", {0.3, 4.0}));  // 4 rad is clamped to 170 degrees
  EXPECT_NE(log.text().find("clamped to 2.96706"), std::string::npos) << log.text();
  EXPECT_EQ(gate.received(), 1u);
  EXPECT_EQ(gate.rejected(), 2u);
  sim.step();
  const RobotSpec& r = sim.world().robots[0].spec;
  const auto& target = sim.state().robots[0].joint_target;
  EXPECT_EQ(target[static_cast<std::size_t>(r.joint_index("left_flipper_joint"))], 0.3);
  EXPECT_NEAR(target[static_cast<std::size_t>(r.joint_index("right_flipper_joint"))], 170 * M_PI / 180, 1e-12);
}

TEST(CommandGate, AStampAheadOfSimTimeBeyondTheToleranceIsRefused) {
  const SimTime now = SimTime::from_seconds(10);
  EXPECT_EQ(stamp_problem(SimTime{0}, now), "");                           // unset
  EXPECT_EQ(stamp_problem(SimTime::from_seconds(3), now), "");             // the past
  EXPECT_EQ(stamp_problem(now, now), "");
  EXPECT_EQ(stamp_problem(now + kFutureStampTolerance, now), "");          // at the tolerance
  EXPECT_NE(stamp_problem(now + kFutureStampTolerance + SimTime{1}, now), "");  // 1 ns beyond
  EXPECT_EQ(kFutureStampTolerance.ns, 500'000'000);
  // a publisher on wall-clock time
  const std::string wall = stamp_problem(SimTime::from_seconds(1.7e9), now);
  EXPECT_EQ(wall.rfind("header.stamp 1700000000.000 s is 1699999990.000 s ahead of the simulation's time 10.000 s (at most 0.5 s is "
                       "allowed; a publisher on wall-clock time?",
                       0),
            0u)
      << wall;
  // at the start of a run every set stamp beyond 0.5 s is ahead
  EXPECT_EQ(stamp_problem(SimTime{1}, SimTime{0}), "");
  EXPECT_NE(stamp_problem(SimTime::from_seconds(1), SimTime{0}), "");
}

}  // namespace
}  // namespace rescuesim
