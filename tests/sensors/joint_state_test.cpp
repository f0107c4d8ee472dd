// Joint states: every moving joint's name, position, velocity and effort in spec order; fixed
// joints (which never move and are on /tf_static) left out.

#include "sensors/joint_state.h"

#include <gtest/gtest.h>

namespace rescuesim {
namespace {

JointSpec joint(const std::string& name, JointSpec::Type type) {
  JointSpec j;
  j.name = name;
  j.type = type;
  return j;
}

TEST(JointStates, MovingJointsInSpecOrderFixedOnesSkipped) {
  // four joints: a revolute pan, a fixed camera mount, a prismatic lift and a continuous wheel
  World world;
  RobotInstance robot;
  robot.name = "r";
  robot.spec.joints = {joint("pan", JointSpec::Type::revolute), joint("camera_mount", JointSpec::Type::fixed),
                       joint("lift", JointSpec::Type::prismatic), joint("wheel", JointSpec::Type::continuous)};
  world.robots.push_back(robot);
  State state;
  RobotState rs;
  rs.q = {0.5, 0.0, 0.12, -3.0};
  rs.qd = {0.1, 0.0, 0.02, 6.5};
  rs.effort = {1.5, 0.0, 20.0, -0.75};
  state.robots.push_back(rs);

  const msg::JointState js = sample_joint_states(world, state, RobotIndex(0), SimTime::from_ms(50));
  EXPECT_EQ(js.header.stamp, SimTime::from_ms(50));
  EXPECT_EQ(js.header.frame_id, "");
  EXPECT_EQ(js.name, (std::vector<std::string>{"pan", "lift", "wheel"}));
  EXPECT_EQ(js.position, (std::vector<double>{0.5, 0.12, -3.0}));
  EXPECT_EQ(js.velocity, (std::vector<double>{0.1, 0.02, 6.5}));
  EXPECT_EQ(js.effort, (std::vector<double>{1.5, 20.0, -0.75}));
}

TEST(JointStates, OnlyFixedJointsGiveAnEmptyMessage) {
  World world;
  RobotInstance robot;
  robot.spec.joints = {joint("mount", JointSpec::Type::fixed)};
  world.robots.push_back(robot);
  State state;
  RobotState rs;
  rs.q = rs.qd = rs.effort = {0.0};
  state.robots.push_back(rs);
  const msg::JointState js = sample_joint_states(world, state, RobotIndex(0), SimTime{});
  EXPECT_TRUE(js.name.empty());
  EXPECT_TRUE(js.position.empty());
  EXPECT_TRUE(js.velocity.empty());
  EXPECT_TRUE(js.effort.empty());
}

}  // namespace
}  // namespace rescuesim
