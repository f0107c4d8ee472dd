// Robots from SDF models: tests/data/sdf/models/skid_steer (gz-sim's diff-drive system, four
// wheels) and skid_steer_classic (the same robot with ROS 1's libgazebo_ros_diff_drive.so).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "import/sdf/sdf_test_files.h"

namespace rescuesim {
namespace {

using ::testing::HasSubstr;
using namespace sdf_test;
using urdf_test::joint_named;
using urdf_test::link_named;

void expect_skid_steer(const SdfRobot& r) {
  const RobotSpec& s = r.spec;
  ASSERT_EQ(s.links.size(), 5u);
  EXPECT_EQ(s.links.front().name, "chassis");
  EXPECT_DOUBLE_EQ(s.links.front().mass, 10.0);
  EXPECT_NEAR(s.total_mass(), 12.0, 1e-12);
  ASSERT_EQ(s.joints.size(), 4u);
  for (const auto& j : s.joints) {
    EXPECT_EQ(j.type, JointSpec::Type::continuous) << j.name;
    EXPECT_EQ(j.parent, "chassis");
    EXPECT_LT((j.axis - Vec3::UnitY()).norm(), 1e-12) << j.name;
    EXPECT_EQ(j.control, JointSpec::Control::velocity) << j.name;
  }
  // the front left wheel in the chassis frame: wheelbase 0.4, track 0.5, both at the same height
  expect_pose(joint_named(s, "front_left_wheel_joint").X_PJ, Pose3{Vec3(0.2, 0.25, 0), Quat::Identity()});
  expect_pose(joint_named(s, "rear_right_wheel_joint").X_PJ, Pose3{Vec3(-0.2, -0.25, 0), Quat::Identity()});
  const LinkSpec& wheel = link_named(s, "front_left_wheel");
  EXPECT_DOUBLE_EQ(wheel.mass, 0.5);
  EXPECT_NEAR(wheel.inertia.y(), 0.0025, 1e-12);
  EXPECT_EQ(s.drive.left_wheels.size(), 2u);
  EXPECT_EQ(s.drive.right_wheels.size(), 2u);
  EXPECT_THAT(s.drive.left_wheels, ::testing::UnorderedElementsAre("front_left_wheel_joint", "rear_left_wheel_joint"));
  EXPECT_DOUBLE_EQ(s.drive.wheel_radius, 0.1);
  EXPECT_DOUBLE_EQ(s.drive.track_width, 0.5);
  for (double sign : s.drive.left_signs) EXPECT_EQ(sign, 1.0);
  // the wheel shapes: one collision cylinder and one visible cylinder
  int collides = 0, visible = 0;
  for (const auto& sh : wheel.shapes) collides += sh.collides, visible += sh.visible;
  EXPECT_EQ(collides, 1);
  EXPECT_EQ(visible, 1);
}

TEST(SdfRobot, SkidSteerFromGzSimDiffDrive) {
  const SdfRobot r = load_sdf_robot("model://skid_steer", isolated());
  EXPECT_EQ(r.spec.model, "skid_steer");
  expect_skid_steer(r);
  EXPECT_EQ(r.drive_source, "plugin gz-sim-diff-drive-system");
  EXPECT_EQ(r.spec.source_file, (models_dir() / "skid_steer" / "model.sdf").string());
}

TEST(SdfRobot, SkidSteerFromClassicDiffDrive) {
  const SdfRobot r = load_sdf_robot("model://skid_steer_classic", isolated());
  expect_skid_steer(r);
  EXPECT_EQ(r.drive_source, "plugin libgazebo_ros_diff_drive.so");
}

TEST(SdfRobot, LidarSensorAtTenHertzWith360Rays) {
  const SdfRobot r = load_sdf_robot((models_dir() / "skid_steer").string(), isolated());
  int lidars = 0;
  for (const auto& s : r.spec.sensors) {
    if (s.type != SensorSpec::Type::lidar) continue;
    ++lidars;
    EXPECT_EQ(s.name, "lidar");
    EXPECT_EQ(s.link, "chassis");
    EXPECT_DOUBLE_EQ(s.rate, 10.0);
    EXPECT_EQ(s.lidar.samples, 360);
    EXPECT_DOUBLE_EQ(s.lidar.max_range, 12.0);
    expect_pose(s.X_LS, Pose3{Vec3(0.2, 0, 0.1), Quat::Identity()});
  }
  EXPECT_EQ(lidars, 1);
  // the standard sensors are added
  EXPECT_NE(r.spec.find_sensor("odometry"), nullptr);
  EXPECT_NE(r.spec.find_sensor("joint_states"), nullptr);
}

TEST(SdfRobot, ModelFileByPath) {
  const SdfRobot r = load_sdf_robot((models_dir() / "skid_steer" / "model.sdf").string(), isolated());
  EXPECT_EQ(r.spec.links.size(), 5u);
}

TEST(SdfRobot, JointFrameOffsetFromTheChildAndAxisInTheParentModelFrame) {
  // the joint sits 0.1 m along the child's x; its axis is written in the model frame, where the
  // child is turned a quarter about z
  const std::string text = R"(<?xml version="1.0"?>
<sdf version="1.9">
  <model name="arm">
    <link name="base">
      <inertial><mass>1</mass><inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz></inertia></inertial>
    </link>
    <link name="tip">
      <pose>1 0 0 0 0 1.5707963267948966</pose>
      <inertial><pose>0.2 0 0 0 0 0</pose><mass>1</mass><inertia><ixx>0.01</ixx><iyy>0.02</iyy><izz>0.03</izz></inertia></inertial>
    </link>
    <joint name="hinge" type="revolute">
      <pose>0.1 0 0 0 0 0</pose>
      <parent>base</parent>
      <child>tip</child>
      <axis><xyz expressed_in="__model__">1 0 0</xyz><limit><lower>-1</lower><upper>1</upper></limit></axis>
    </joint>
  </model>
</sdf>
)";
  TempDir dir;
  const auto file = dir.write("arm.sdf", text);
  const SdfRobot r = load_sdf_robot(file.string(), isolated({}));
  const JointSpec& j = joint_named(r.spec, "hinge");
  // the joint frame: the tip's frame moved 0.1 along the tip's x (= model y)
  expect_pose(j.X_PJ, Pose3::from_rpy(Vec3(1, 0.1, 0), 0, 0, M_PI / 2));
  // model x in the joint frame (turned a quarter): -y
  EXPECT_LT((j.axis - Vec3(0, -1, 0)).norm(), 1e-9);
  EXPECT_DOUBLE_EQ(j.lower, -1);
  EXPECT_DOUBLE_EQ(j.upper, 1);
  // the tip's centre of mass, 0.2 along the tip's x, is 0.1 from the joint
  EXPECT_LT((link_named(r.spec, "tip").com - Vec3(0.1, 0, 0)).norm(), 1e-9);
  EXPECT_THAT(warnings(r.diagnostics), HasSubstr("no diff-drive plugin"));
}

}  // namespace
}  // namespace rescuesim

namespace rescuesim {
namespace {

// Lights on a model's links become the robot's lamps (tests/data/sdf/models/lamp_bot): a spot
// keeps half SDF's whole cone angles, and its pose's pitch of -90 degrees turns SDF's default
// direction (down) forwards, where a lamp shines along its frame's x; a point light lights every
// direction; a directional light is left out with a warning. They are on, as in Gazebo.
TEST(SdfRobot, LinkLightsBecomeTheRobotsLamps) {
  const SdfRobot r = load_sdf_robot((sdf_test::models_dir() / "lamp_bot").string(), sdf_test::isolated());
  const RobotSpec& s = r.spec;
  ASSERT_EQ(s.lights.size(), 2u);
  EXPECT_TRUE(s.lights_on);
  const RobotLightSpec& head = s.lights[0];
  EXPECT_EQ(head.name, "headlight");
  EXPECT_EQ(head.link, "chassis");
  EXPECT_LT((head.X_LF.p - Vec3(0.3, 0, 0.05)).norm(), 1e-12);
  EXPECT_LT((head.X_LF.q * Vec3::UnitX() - Vec3::UnitX()).norm(), 1e-9);
  EXPECT_DOUBLE_EQ(head.cone, 0.5);
  EXPECT_DOUBLE_EQ(head.inner_cone, 0.3);
  EXPECT_DOUBLE_EQ(head.range, 15.0);
  EXPECT_DOUBLE_EQ(head.intensity, 2.0);
  EXPECT_LT((head.color - Vec3(1, 0.9, 0.8)).norm(), 1e-6);
  const RobotLightSpec& beacon = s.lights[1];
  EXPECT_EQ(beacon.name, "beacon");
  EXPECT_DOUBLE_EQ(beacon.cone, M_PI);
  EXPECT_DOUBLE_EQ(beacon.range, 5.0);
  bool warned = false;
  for (const auto& d : r.diagnostics.items()) warned = warned || d.message.find("directional light 'sun_on_a_stick'") != std::string::npos;
  EXPECT_TRUE(warned);
}

}  // namespace
}  // namespace rescuesim
