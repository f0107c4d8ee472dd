// Ground truth: the pose message is the true base pose, and the /tf transforms it adds put the
// robot where it really is, worked out by hand for a robot at (1, 2) facing +y.

#include "sensors/ground_truth.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace rescuesim {
namespace {

/// One robot whose base is at (1, 2, 0.15) m, turned 90° about z (facing +y).
State robot_at_1_2_facing_y() {
  State s;
  RobotState rs;
  rs.base.X_WB = Pose3::from_rpy(Vec3(1, 2, 0.15), 0, 0, std::numbers::pi / 2);
  s.robots.push_back(rs);
  return s;
}

void expect_pose(const Pose3& X, const Vec3& p, double yaw) {
  EXPECT_NEAR(X.p.x(), p.x(), 1e-12);
  EXPECT_NEAR(X.p.y(), p.y(), 1e-12);
  EXPECT_NEAR(X.p.z(), p.z(), 1e-12);
  // a rotation about z by yaw is the quaternion (cos yaw/2, 0, 0, sin yaw/2)
  EXPECT_NEAR(X.q.w(), std::cos(yaw / 2), 1e-12);
  EXPECT_NEAR(X.q.x(), 0, 1e-12);
  EXPECT_NEAR(X.q.y(), 0, 1e-12);
  EXPECT_NEAR(X.q.z(), std::sin(yaw / 2), 1e-12);
}

TEST(GroundTruth, PoseIsTheTrueBasePoseInMap) {
  const msg::PoseStamped p = sample_ground_truth(robot_at_1_2_facing_y(), RobotIndex(0), SimTime::from_ms(250));
  EXPECT_EQ(p.header.stamp, SimTime::from_ms(250));
  EXPECT_EQ(p.header.frame_id, "map");
  // (cos 45°, 0, 0, sin 45°) = (0.70711, 0, 0, 0.70711)
  expect_pose(p.pose, {1, 2, 0.15}, std::numbers::pi / 2);
}

TEST(GroundTruth, MapToOdomCompletesTheChainToTheTruePose) {
  // wheel odometry believes the robot went 0.5 m straight ahead from odom's origin, while it is
  // truly at (1, 2) facing +y: odom must sit at (1, 2) − 0.5 m along +y = (1, 1.5), turned 90°
  State s = robot_at_1_2_facing_y();
  s.robots[0].base.X_WB.p.z() = 0;
  s.robots[0].odom = Pose2{0.5, 0, 0};
  const msg::TFMessage tf = ground_truth_tf(s, RobotIndex(0), SimTime::from_ms(20), {"robot2/odom", "robot2/base_link", false, true});
  ASSERT_EQ(tf.transforms.size(), 1u);
  const msg::TransformStamped& t = tf.transforms[0];
  EXPECT_EQ(t.header.stamp, SimTime::from_ms(20));
  EXPECT_EQ(t.header.frame_id, "map");
  EXPECT_EQ(t.child_frame_id, "robot2/odom");
  expect_pose(t.transform, {1, 1.5, 0}, std::numbers::pi / 2);
}

TEST(GroundTruth, OdomToBaseFromTruthMakesMapToOdomTheIdentity) {
  // with odom -> base_link the true pose, map and odom coincide whatever the wheels say
  State s = robot_at_1_2_facing_y();
  s.robots[0].odom = Pose2{0.5, 0.25, 1.0};
  const msg::TFMessage tf = ground_truth_tf(s, RobotIndex(0), SimTime::from_ms(20), {"odom", "base_footprint", true, true});
  ASSERT_EQ(tf.transforms.size(), 2u);
  EXPECT_EQ(tf.transforms[0].header.frame_id, "odom");
  EXPECT_EQ(tf.transforms[0].child_frame_id, "base_footprint");
  expect_pose(tf.transforms[0].transform, {1, 2, 0.15}, std::numbers::pi / 2);
  EXPECT_EQ(tf.transforms[1].header.frame_id, "map");
  EXPECT_EQ(tf.transforms[1].child_frame_id, "odom");
  expect_pose(tf.transforms[1].transform, {0, 0, 0}, 0);
}

TEST(GroundTruth, NoTransformsWhenNoneAreAskedFor) {
  EXPECT_TRUE(ground_truth_tf(robot_at_1_2_facing_y(), RobotIndex(0), SimTime{}, {"odom", "base_link", false, false}).transforms.empty());
}

}  // namespace
}  // namespace rescuesim
