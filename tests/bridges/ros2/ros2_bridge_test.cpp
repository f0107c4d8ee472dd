// The bridge in-process, seen from a second DDS participant in this process: two robots get
// namespaced topics, /tf_static reaches a late joiner (transient local), a robot's cmd_vel
// moves that robot only, a robot's description reaches a late joiner and its joint_command moves
// its joints, and a participant that cannot start is a clear error.

#include "bridges/ros2/ros2_bridge.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <thread>

#include "bridges/ros2/dds_participant.h"
#include "core/error.h"
#include "msgs/serialize.h"
#include "robots/rescue_robot.h"
#include "sim/simulation.h"
#include "sim/slider_robot.h"
#include "bridges/ros2/dds_loopback.h"
#include "support/dds_domain.h"
#include "support/rig.h"

namespace rescuesim {
namespace {

using ros2::DdsParticipant;

class Ros2BridgeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    testing::pin_cyclone_to_loopback();
  }
  int domain() const { return testing::leased_dds_domain(); }
};

/// Two rescue robots side by side in a 20 m room, facing +x.
Simulation two_robots() {
  WorldSpec spec = testing::room_spec(20.0, {0, -2, 0});
  RobotPlacement second;
  second.name = "robot2";
  second.start = {0, 2, 0};
  spec.robots.push_back(second);
  return Simulation(compile_world(spec, builtin_models()));
}

template <class T>
std::vector<T> take_all(DdsParticipant& p, int reader, const char* type) {
  std::vector<T> out;
  p.take(reader, [&](std::span<const std::uint8_t> bytes) {
    out.push_back(std::get<T>(msg::from_cdr(*msg::find_type(type), bytes)));
  });
  return out;
}

TEST_F(Ros2BridgeTest, NamespacedRobotsLatchedTfStaticAndCommandsForOneRobot) {
  Simulation sim = two_robots();
  Ros2Options o;
  o.domain_id = domain();
  auto bridge = make_ros2_bridge(o);
  bridge->start(sim);
  sim.step();  // publishes /tf_static once, before anyone listens

  DdsParticipant ros(domain(), ros2::participant_user_data());
  ros2::EndpointQos latched{ros2::Reliability::reliable, ros2::Durability::transient_local, 1};
  const int tf_static = ros.create_reader("rt/tf_static", "tf2_msgs::msg::dds_::TFMessage_", latched);
  const int odom2 = ros.create_reader("rt/robot2/odom", "nav_msgs::msg::dds_::Odometry_", {});
  const int cmd2 = ros.create_writer("rt/robot2/cmd_vel", "geometry_msgs::msg::dds_::Twist_", {});
  msg::Twist forward;
  forward.linear.x() = 0.4;
  std::vector<std::uint8_t> cmd;
  msg::to_cdr(forward, cmd);

  std::vector<msg::TFMessage> statics;
  std::vector<msg::Odometry> odoms;
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  SimTime driving_since{-1};
  while (std::chrono::steady_clock::now() < give_up) {
    std::string error;
    if (ros.matched_readers(cmd2) > 0) {
      ASSERT_TRUE(ros.write(cmd2, cmd, &error)) << error;
      if (driving_since.ns < 0) driving_since = sim.time();
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));  // let the command arrive
    sim.step_until(sim.time() + SimTime::from_ms(50));
    for (auto& m : take_all<msg::TFMessage>(ros, tf_static, "tf2_msgs/TFMessage")) statics.push_back(m);
    for (auto& m : take_all<msg::Odometry>(ros, odom2, "nav_msgs/Odometry")) odoms.push_back(m);
    if (driving_since.ns >= 0 && sim.time() - driving_since > SimTime::from_seconds(2.0) && !statics.empty()) break;
  }
  bridge->stop();

  // the late joiner still got /tf_static, with robot2's frames prefixed
  ASSERT_EQ(statics.size(), 1u);
  bool laser2 = false;
  for (const auto& t : statics[0].transforms) {
    laser2 = laser2 || (t.header.frame_id == "robot2/base_link" && t.child_frame_id == "robot2/laser");
  }
  EXPECT_TRUE(laser2);
  ASSERT_FALSE(odoms.empty());
  EXPECT_EQ(odoms.back().header.frame_id, "robot2/odom");
  EXPECT_EQ(odoms.back().child_frame_id, "robot2/base_link");

  // about 2 s at 0.4 m/s moved robot2; robot stayed where it was
  ASSERT_GE(driving_since.ns, 0) << "the bridge's reader on rt/robot2/cmd_vel never matched";
  const Vec3 p1 = sim.state().robots[0].base.X_WB.p, p2 = sim.state().robots[1].base.X_WB.p;
  EXPECT_NEAR(p1.x(), 0.0, 0.01);
  EXPECT_GT(p2.x(), 0.5);
  EXPECT_LT(p2.x(), 0.4 * 2.2);
  EXPECT_NEAR(p2.y(), 2.0, 0.05);
  const BridgeStats st = bridge->stats();
  // only what someone reads is sent: /tf_static (latched, once) and robot2's odometry, which the
  // simulation publishes at 50 Hz of sim time (stamps 0, 20 ms, …): however fast discovery was,
  // the bridge cannot have sent more than the sim time that ran produced, nor fewer than the peer got
  const std::int64_t period = SimTime::from_ms(20).ns;
  const std::uint64_t odom_published = static_cast<std::uint64_t>(sim.time().ns / period) + 1;
  EXPECT_LE(st.sent, 1 + odom_published);
  EXPECT_GE(st.sent, statics.size() + odoms.size());
  // the peer got them in order on the 20 ms grid; on a reliable keep-last-10 link a sample is lost
  // only when the bridge falls 10 samples (200 ms of sim time) behind the peer's reads, so at least
  // half of those between its first and last must have arrived
  for (std::size_t i = 1; i < odoms.size(); ++i) {
    const std::int64_t gap = (odoms[i].header.stamp - odoms[i - 1].header.stamp).ns;
    ASSERT_GT(gap, 0) << "odometry " << i << " out of order";
    EXPECT_EQ(gap % period, 0) << "odometry " << i << " off the 50 Hz grid";
  }
  const std::int64_t span = (odoms.back().header.stamp - odoms.front().header.stamp).ns / period + 1;
  EXPECT_GE(static_cast<std::int64_t>(odoms.size()), span / 2);
  EXPECT_GT(st.received, 10u);
  EXPECT_EQ(st.rejected, 0u);
}

TEST_F(Ros2BridgeTest, RobotDescriptionReachesALateJoinerAndJointCommandsMoveJoints) {
  Simulation sim(testing::slider_world());
  Ros2Options o;
  o.domain_id = domain();
  auto bridge = make_ros2_bridge(o);
  bridge->start(sim);
  sim.step();  // publishes robot_description once, before anyone listens

  // robot_state_publisher's QoS for robot_description: reliable, transient local, depth 1
  DdsParticipant ros(domain(), ros2::participant_user_data());
  ros2::EndpointQos latched{ros2::Reliability::reliable, ros2::Durability::transient_local, 1};
  const int description = ros.create_reader("rt/robot_description", "std_msgs::msg::dds_::String_", latched);
  const int command = ros.create_writer("rt/joint_command", "sensor_msgs::msg::dds_::JointState_", {});
  msg::JointState lift;
  lift.name = {"lift"};
  lift.position = {0.15};
  msg::JointState wheel;
  wheel.name = {"wheel"};
  wheel.velocity = {1.0};
  std::vector<std::uint8_t> lift_bytes, wheel_bytes;
  msg::to_cdr(lift, lift_bytes);
  msg::to_cdr(wheel, wheel_bytes);

  std::vector<msg::String> texts;
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (std::chrono::steady_clock::now() < give_up) {
    std::string error;
    if (ros.matched_readers(command) > 0) {
      ASSERT_TRUE(ros.write(command, wheel_bytes, &error)) << error;
      ASSERT_TRUE(ros.write(command, lift_bytes, &error)) << error;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    sim.step_until(sim.time() + SimTime::from_ms(50));
    for (auto& m : take_all<msg::String>(ros, description, "std_msgs/String")) texts.push_back(m);
    if (!texts.empty() && std::abs(sim.state().robots[0].q[0] - 0.15) < 1e-3) break;
  }
  bridge->stop();

  ASSERT_EQ(texts.size(), 1u);
  EXPECT_EQ(texts[0].data, testing::kSliderDescription);
  EXPECT_EQ(sim.state().robots[0].joint_target[0], 0.15);
  EXPECT_NEAR(sim.state().robots[0].q[0], 0.15, 1e-3);
  const BridgeStats st = bridge->stats();
  EXPECT_GT(st.received, 0u);
  EXPECT_GT(st.rejected, 0u);  // the wheel commands: cmd_vel drives wheels
}

TEST_F(Ros2BridgeTest, StartFailsWithAReasonWhenNoParticipantCanBeMade) {
  Simulation sim = two_robots();
  Ros2Options o;
  o.domain_id = 5000;  // beyond what DDS's port mapping allows
  auto bridge = make_ros2_bridge(o);
  try {
    bridge->start(sim);
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("ROS 2 bridge: Cyclone DDS could not create a participant on domain 5000"), std::string::npos)
        << e.what();
  }
  bridge->stop();  // harmless after a failed start
}

}  // namespace
}  // namespace rescuesim
