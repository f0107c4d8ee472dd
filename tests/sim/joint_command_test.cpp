// Joint commands, robot descriptions and the TF of a URDF-like robot, on the hand-built slider
// robot (tests/sim/slider_robot.h): what command_joints refuses and why, a prismatic joint driven
// to a commanded position (checked against the link's pose in physics and against /tf), a
// velocity-controlled joint at its commanded speed, the root link as odometry's child frame, and
// the latched robot_description.

#include <gtest/gtest.h>

#include <cmath>

#include "robots/rescue_robot.h"
#include "sim/simulation.h"
#include "sim/slider_robot.h"
#include "support/rig.h"

namespace rescuesim {
namespace {

using testing::kSliderDescription;
using testing::slider_world;

msg::JointState command(std::vector<std::string> names, std::vector<double> position, std::vector<double> velocity = {}) {
  msg::JointState js;
  js.name = std::move(names);
  js.position = std::move(position);
  js.velocity = std::move(velocity);
  return js;
}

/// The reason command_joints gives for refusing `c` ("" when it accepts it).
std::string refusal(Simulation& sim, const msg::JointState& c, int robot = 0) {
  const CommandOutcome outcome = sim.command_joints(RobotIndex(robot), c);
  if (outcome) return "";
  EXPECT_FALSE(outcome.reason.empty());
  return outcome.reason;
}

TEST(JointCommand, OnlyControlledJointsThatNothingElseDrivesAreCommandable) {
  const World w = slider_world();
  const RobotSpec& spec = w.robots[0].spec;
  std::vector<std::string> commandable;
  for (std::size_t j = 0; j < spec.joints.size(); ++j) {
    if (is_commandable(spec, j)) commandable.push_back(spec.joints[j].name);
  }
  EXPECT_EQ(commandable, (std::vector<std::string>{"lift", "spin"}));
  EXPECT_TRUE(has_commandable_joints(spec));
  // the rescue robot's moving joints are its wheels and its head: nothing for joint_command
  EXPECT_FALSE(has_commandable_joints(rescue_robot()));
}

TEST(JointCommand, RefusalsSayWhyAndQueueNothing) {
  Simulation sim(slider_world());
  const double nan = std::nan("");
  EXPECT_EQ(refusal(sim, command({"nope"}, {0.1})), "'nope' is not a joint of slider");
  EXPECT_EQ(refusal(sim, command({"wheel"}, {}, {1.0})), "'wheel' is a drive wheel (use cmd_vel): not commandable");
  EXPECT_EQ(refusal(sim, command({"pan"}, {0.1})), "'pan' is a head joint (use head/command): not commandable");
  EXPECT_EQ(refusal(sim, command({"mount"}, {0.1})), "'mount' is a fixed joint: not commandable");
  EXPECT_EQ(refusal(sim, command({"flap"}, {0.1})), "'flap' is a passive joint (no controller): not commandable");
  EXPECT_EQ(refusal(sim, command({"follow"}, {0.1})), "'follow' is a mimic joint (it follows its leader): not commandable");
  EXPECT_EQ(refusal(sim, command({"lift"}, {nan})), "position[0] ('lift') is not finite");
  EXPECT_EQ(refusal(sim, command({"lift", "spin"}, {0.1, 0}, {0, INFINITY})), "velocity[1] ('spin') is not finite");
  EXPECT_EQ(refusal(sim, command({"lift", "spin"}, {0.1})), "position has 1 values for 2 names (give one per name, or none)");
  EXPECT_EQ(refusal(sim, command({"lift"}, {0.1}, {1, 2})), "velocity has 2 values for 1 names (give one per name, or none)");
  EXPECT_EQ(refusal(sim, command({"spin"}, {1.0})), "'spin' is velocity-controlled but the command has no velocity");
  EXPECT_EQ(refusal(sim, command({"lift"}, {}, {0.1})), "'lift' is position-controlled but the command has no position");
  EXPECT_EQ(refusal(sim, command({"lift", "lift"}, {0.1, 0.2})), "'lift' is named twice");
  EXPECT_EQ(refusal(sim, command({}, {})), "no joint names");
  EXPECT_EQ(refusal(sim, command({"lift"}, {0.1}), 1), "no robot 1");
  EXPECT_FALSE(sim.command_joints(RobotIndex(), command({"lift"}, {0.1})));  // without a reason asked for
  // one bad name spoils the whole command: nothing of it is applied
  EXPECT_NE(refusal(sim, command({"lift", "wheel"}, {0.1, 0}, {0, 1})), "");
  EXPECT_EQ(sim.discard_commands(), 0u);
  // the accepted ones queue; a NaN in a value the joint does not use is no reason to refuse
  EXPECT_EQ(refusal(sim, command({"lift", "spin"}, {0.1, nan}, {nan, 1.0})), "");
  EXPECT_EQ(sim.discard_commands(), 1u);
}

TEST(JointCommand, PrismaticJointReachesItsPositionAndTfIsATranslationAlongItsAxis) {
  Simulation sim(slider_world());
  msg::TFMessage last_lift, last_spin;
  sim.bus().subscribe("/tf", [&](const Topic&, const msg::Message& m) {
    for (const auto& t : std::get<msg::TFMessage>(m).transforms) {
      if (t.child_frame_id == "lift_link") last_lift.transforms = {t};
      if (t.child_frame_id == "spin_link") last_spin.transforms = {t};
    }
  });
  sim.step();
  ASSERT_TRUE(sim.command_joints(RobotIndex(0), command({"lift", "spin"}, {0.15, 0}, {0, 1.0})));
  // nothing moves before the next step boundary
  EXPECT_EQ(sim.state().robots[0].joint_target[0], 0.0);
  // kp = 8/s and 0.5 m/s at most: well settled after 3 s
  sim.step_until(SimTime::from_seconds(3.0));
  ASSERT_FALSE(sim.in_trouble()) << sim.state().trouble.first;
  const RobotSpec& spec = sim.world().robots[0].spec;
  const RobotState& rs = sim.state().robots[0];
  EXPECT_EQ(rs.joint_target[0], 0.15);
  EXPECT_EQ(rs.joint_target[1], 1.0);
  EXPECT_NEAR(rs.q[0], 0.15, 1e-3);
  EXPECT_NEAR(rs.qd[1], 1.0, 0.05);

  // in physics, the lift link slid along the base's x axis, without turning
  const int lift_link = spec.link_index("lift_link");
  const Pose3 X_BL = rs.X_WL[0].inverse() * rs.X_WL[static_cast<std::size_t>(lift_link)];
  EXPECT_NEAR((X_BL.p - Vec3(0.15, 0, 0.2)).norm(), 0, 1e-3) << X_BL.p.transpose();
  EXPECT_NEAR(X_BL.q.angularDistance(Quat::Identity()), 0, 1e-3);

  // on /tf (at 50 Hz, so the last one is at t = 3 s, this very state): X_PJ, then q along the axis
  ASSERT_EQ(last_lift.transforms.size(), 1u);
  const msg::TransformStamped& t = last_lift.transforms[0];
  EXPECT_EQ(t.header.stamp, sim.time());
  EXPECT_EQ(t.header.frame_id, "base_footprint");
  const Pose3 motion = spec.joints[0].X_PJ.inverse() * t.transform;
  EXPECT_NEAR((motion.p - rs.q[0] * Vec3::UnitX()).norm(), 0, 1e-12) << motion.p.transpose();
  EXPECT_NEAR(motion.q.angularDistance(Quat::Identity()), 0, 1e-12);
  // a revolute joint's stays a rotation about its axis
  ASSERT_EQ(last_spin.transforms.size(), 1u);
  const Pose3 turn = spec.joints[1].X_PJ.inverse() * last_spin.transforms[0].transform;
  EXPECT_NEAR(turn.p.norm(), 0, 1e-12);
  EXPECT_NEAR(turn.q.angularDistance(Quat(Eigen::AngleAxisd(rs.q[1], Vec3::UnitZ()))), 0, 1e-9);
}

TEST(JointCommand, PositionTargetsAreClampedToTheJointLimits) {
  Simulation sim(slider_world());
  ASSERT_TRUE(sim.command_joints(RobotIndex(0), command({"lift"}, {5.0})));
  sim.step_until(SimTime::from_seconds(2.0));
  EXPECT_EQ(sim.state().robots[0].joint_target[0], 0.2);
  EXPECT_NEAR(sim.state().robots[0].q[0], 0.2, 2e-3);
  ASSERT_TRUE(sim.command_joints(RobotIndex(0), command({"lift"}, {-5.0})));
  sim.step();
  EXPECT_EQ(sim.state().robots[0].joint_target[0], -0.1);
}

TEST(JointCommand, OdometryChildFrameIsTheRootLink) {
  Simulation sim(slider_world());
  std::string odom_child, tf_child;
  sim.bus().subscribe("/odom", [&](const Topic&, const msg::Message& m) { odom_child = std::get<msg::Odometry>(m).child_frame_id; });
  sim.bus().subscribe("/tf", [&](const Topic&, const msg::Message& m) {
    for (const auto& t : std::get<msg::TFMessage>(m).transforms) {
      if (t.header.frame_id == "odom") tf_child = t.child_frame_id;
    }
  });
  sim.step();
  EXPECT_EQ(odom_child, "base_footprint");
  EXPECT_EQ(tf_child, "base_footprint");
}

TEST(RobotDescription, LatchedOnceForRobotsThatHaveOne) {
  Simulation sim(slider_world());
  const TopicId id = sim.bus().find("/robot_description");
  ASSERT_NE(id, kNoTopic);
  const Topic& topic = sim.bus().topic(id);
  EXPECT_EQ(topic.type, "std_msgs/String");
  EXPECT_TRUE(topic.latched);
  EXPECT_EQ(topic.robot, RobotIndex(0));
  sim.step_until(SimTime::from_seconds(0.5));
  EXPECT_EQ(sim.bus().count(id), 1u);
  // a subscriber that comes late still gets it
  std::string text;
  sim.bus().subscribe("/robot_description", [&](const Topic&, const msg::Message& m) { text = std::get<msg::String>(m).data; });
  EXPECT_EQ(text, kSliderDescription);

  // the built-in rescue robot has no description: no topic
  Simulation rescue(compile_world(testing::room_spec(), builtin_models()));
  EXPECT_EQ(rescue.bus().find("/robot_description"), kNoTopic);
}

TEST(RobotDescription, NamespacedWithSeveralRobots) {
  WorldSpec spec = testing::slider_room("arm");
  spec.robots[0].start = {-1.5, 0, 0};
  RobotPlacement rescue;
  rescue.name = "rescue";
  rescue.start = {1.5, 0, 0};
  spec.robots.push_back(rescue);
  auto models = builtin_models();
  models["slider"] = testing::slider_robot();
  Simulation sim(compile_world(spec, models));
  EXPECT_NE(sim.bus().find("/arm/robot_description"), kNoTopic);
  EXPECT_EQ(sim.bus().find("/robot_description"), kNoTopic);
  EXPECT_EQ(sim.bus().find("/rescue/robot_description"), kNoTopic);
  std::string odom_child;
  sim.bus().subscribe("/arm/odom", [&](const Topic&, const msg::Message& m) { odom_child = std::get<msg::Odometry>(m).child_frame_id; });
  sim.step();
  EXPECT_EQ(odom_child, "arm/base_footprint");
}

}  // namespace
}  // namespace rescuesim

namespace rescuesim {
namespace {

TEST(Lights, TheLightsTopicSwitchesTheRobotsLampsAtTheNextStep) {
  // what a bridge does with std_msgs/Bool on /lights: submit_input, then the next step hands it over
  Simulation sim(compile_world(testing::room_spec(), builtin_models()));
  ASSERT_FALSE(sim.world().robots[0].spec.lights.empty());  // the rescue robot's head lamp
  const std::vector<HostInput> inputs = sim.inputs();
  std::size_t lights = inputs.size();
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    if (inputs[i].topic == "/lights") lights = i;
  }
  ASSERT_LT(lights, inputs.size());
  EXPECT_EQ(inputs[lights].type, "std_msgs/Bool");
  EXPECT_FALSE(sim.state().robots[0].lights_on);
  EXPECT_FALSE(sim.submit_input(lights, msg::String{"on"}).accepted);  // the wrong type
  EXPECT_TRUE(sim.submit_input(lights, msg::Bool{true}).accepted);
  EXPECT_FALSE(sim.state().robots[0].lights_on);  // not before the step
  sim.step();
  EXPECT_TRUE(sim.state().robots[0].lights_on);
  sim.submit_input(lights, msg::Bool{false});
  sim.step();
  EXPECT_FALSE(sim.state().robots[0].lights_on);
}

}  // namespace
}  // namespace rescuesim
