// The per-kind table: one row per sensor type in enum order, the names scenario files use, the
// ROS types and extra topics the simulation advertises, and which kinds are cameras.

#include "world/sensor_spec.h"

#include <gtest/gtest.h>

#include <string>

namespace rescuesim {
namespace {

using T = SensorSpec::Type;

SensorSpec of(T type) {
  SensorSpec s;
  s.type = type;
  return s;
}

TEST(SensorKinds, OneRowPerTypeInEnumOrderNamedAsScenariosSpellThem) {
  const auto kinds = sensor_kinds();
  ASSERT_EQ(kinds.size(), 10u);
  const char* names[] = {"lidar",        "sonar",   "imu",          "odometry",     "ground_truth",
                         "joint_states", "contact", "color_camera", "depth_camera", "thermal_camera"};
  for (std::size_t i = 0; i < kinds.size(); ++i) {
    EXPECT_EQ(static_cast<std::size_t>(kinds[i].type), i);
    EXPECT_EQ(std::string(kinds[i].name), names[i]);
    EXPECT_EQ(&sensor_kind(kinds[i].type), &kinds[i]);
    EXPECT_EQ(std::string(sensor_type_name(kinds[i].type)), names[i]);
  }
}

TEST(SensorKinds, ExactlyTheThreeRenderedKindsAreCameras) {
  for (const auto& k : sensor_kinds()) {
    const bool camera = k.type == T::color_camera || k.type == T::depth_camera || k.type == T::thermal_camera;
    EXPECT_EQ(of(k.type).is_camera(), camera) << k.name;
  }
}

TEST(SensorKinds, OdometryAndGroundTruthAreNotMounts) {
  for (const auto& k : sensor_kinds()) EXPECT_EQ(k.mounted, k.type != T::odometry && k.type != T::ground_truth) << k.name;
}

TEST(SensorKinds, MainTopicTypes) {
  EXPECT_STREQ(of(T::sonar).ros_type(), "sensor_msgs/Range");
  EXPECT_STREQ(of(T::ground_truth).ros_type(), "geometry_msgs/PoseStamped");
  EXPECT_STREQ(of(T::contact).ros_type(), "rescuesim_msgs/Contacts");
  EXPECT_STREQ(of(T::thermal_camera).ros_type(), "sensor_msgs/Image");
  // a planar lidar publishes a LaserScan, a 16-layer one a point cloud
  SensorSpec lidar = of(T::lidar);
  EXPECT_STREQ(lidar.ros_type(), "sensor_msgs/LaserScan");
  lidar.lidar.layers = 16;
  EXPECT_STREQ(lidar.ros_type(), "sensor_msgs/PointCloud2");
  // layers mean nothing to other kinds
  SensorSpec imu = of(T::imu);
  imu.lidar.layers = 16;
  EXPECT_STREQ(imu.ros_type(), "sensor_msgs/Imu");
}

TEST(SensorKinds, ExtraTopicsBesideTheMainOne) {
  EXPECT_EQ(of(T::lidar).extra_topic(), nullptr);
  EXPECT_EQ(of(T::color_camera).extra_topic(), nullptr);
  const SensorExtraTopic* mono8 = of(T::thermal_camera).extra_topic();
  ASSERT_NE(mono8, nullptr);
  EXPECT_STREQ(mono8->name, "image_mono8");
  EXPECT_STREQ(mono8->ros_type, "sensor_msgs/Image");
  // a depth camera's point cloud is on unless its point_cloud setting is off
  SensorSpec depth = of(T::depth_camera);
  ASSERT_NE(depth.extra_topic(), nullptr);
  EXPECT_STREQ(depth.extra_topic()->name, "points");
  EXPECT_STREQ(depth.extra_topic()->ros_type, "sensor_msgs/PointCloud2");
  depth.camera.point_cloud = false;
  EXPECT_EQ(depth.extra_topic(), nullptr);
  // the switch is the depth camera's only: a thermal camera ignores point_cloud
  SensorSpec thermal = of(T::thermal_camera);
  thermal.camera.point_cloud = false;
  EXPECT_NE(thermal.extra_topic(), nullptr);
}

}  // namespace
}  // namespace rescuesim
