#include "world/sensor_spec.h"

#include <cstddef>

#include "core/error.h"

namespace rescuesim {

namespace {

using T = SensorSpec::Type;

// one row per kind, in enum order (checked below); unnamed fields keep SensorKindInfo's defaults
constexpr std::array<SensorKindInfo, 10> kKinds{{
    {.type = T::lidar, .name = "lidar", .ros_type = "sensor_msgs/LaserScan", .layered_ros_type = "sensor_msgs/PointCloud2"},
    {.type = T::sonar, .name = "sonar", .ros_type = "sensor_msgs/Range"},
    {.type = T::imu, .name = "imu", .ros_type = "sensor_msgs/Imu"},
    {.type = T::odometry, .name = "odometry", .ros_type = "nav_msgs/Odometry", .mounted = false},
    {.type = T::ground_truth, .name = "ground_truth", .ros_type = "geometry_msgs/PoseStamped", .mounted = false},
    {.type = T::joint_states, .name = "joint_states", .ros_type = "sensor_msgs/JointState"},
    {.type = T::contact, .name = "contact", .ros_type = "rescuesim_msgs/Contacts"},
    {.type = T::color_camera, .name = "color_camera", .ros_type = "sensor_msgs/Image", .camera = true},
    {.type = T::depth_camera,
     .name = "depth_camera",
     .ros_type = "sensor_msgs/Image",
     .camera = true,
     .extra = {"points", "sensor_msgs/PointCloud2"},
     .extra_switch = &CameraSpec::point_cloud},
    {.type = T::thermal_camera,
     .name = "thermal_camera",
     .ros_type = "sensor_msgs/Image",
     .camera = true,
     .extra = {"image_mono8", "sensor_msgs/Image"}},
}};

constexpr bool rows_in_enum_order() {
  for (std::size_t i = 0; i < kKinds.size(); ++i) {
    if (static_cast<std::size_t>(kKinds[i].type) != i) return false;
  }
  return true;
}
static_assert(rows_in_enum_order(), "kKinds: one row per SensorSpec::Type, in enum order");

}  // namespace

const SensorKindInfo& sensor_kind(SensorSpec::Type t) {
  // a kind appended to the enum without its row lands here (the static_assert checks the rest)
  RS_DEMAND(static_cast<std::size_t>(t) < kKinds.size(), "sensor_kind: a SensorSpec::Type without a row in kKinds (world/sensor_spec.cpp)");
  return kKinds[static_cast<std::size_t>(t)];
}

std::span<const SensorKindInfo> sensor_kinds() { return kKinds; }

const char* sensor_type_name(SensorSpec::Type t) { return sensor_kind(t).name; }

const SensorKindInfo& SensorSpec::kind() const { return sensor_kind(type); }

bool SensorSpec::is_camera() const { return kind().camera; }

const char* SensorSpec::ros_type() const {
  const SensorKindInfo& k = kind();
  return k.layered_ros_type && lidar.layers > 1 ? k.layered_ros_type : k.ros_type;
}

const SensorExtraTopic* SensorSpec::extra_topic() const {
  const SensorKindInfo& k = kind();
  if (!k.extra.name) return nullptr;
  if (k.extra_switch && !(camera.*k.extra_switch)) return nullptr;
  return &k.extra;
}

}  // namespace rescuesim
