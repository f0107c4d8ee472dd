#pragma once
/// Neutral message structs mirroring ROS message shapes (sensor_msgs, nav_msgs,
/// geometry_msgs, tf2_msgs, rosgraph_msgs, std_msgs). The simulation publishes these on its Bus;
/// serialisers to ROS 1, CDR and JSON (later in this folder) and the bridges turn them into
/// wire formats. Units SI; frames per REP-103/105; stamps are sim time.

#include <array>
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include "core/pose.h"
#include "core/sim_time.h"

namespace rescuesim::msg {

/// std_msgs/Header (ROS 1 adds a seq counter at serialisation).
struct Header {
  SimTime stamp;
  std::string frame_id;
};

/// rosgraph_msgs/Clock.
struct Clock {
  SimTime clock;
};

/// sensor_msgs/LaserScan. Ranges follow REP-117: -inf below range_min, +inf for no return,
/// NaN for an invalid measurement.
struct LaserScan {
  Header header;
  float angle_min = 0, angle_max = 0, angle_increment = 0;  ///< rad
  float time_increment = 0, scan_time = 0;                  ///< s
  float range_min = 0, range_max = 0;                       ///< m
  std::vector<float> ranges;
  std::vector<float> intensities;
};

/// sensor_msgs/Range.
struct Range {
  static constexpr std::uint8_t kUltrasound = 0, kInfrared = 1;
  Header header;
  std::uint8_t radiation_type = kUltrasound;
  float field_of_view = 0, min_range = 0, max_range = 0, range = 0;
};

/// sensor_msgs/Imu.
struct Imu {
  Header header;
  Quat orientation = Quat::Identity();
  std::array<double, 9> orientation_covariance{};
  Vec3 angular_velocity = Vec3::Zero();
  std::array<double, 9> angular_velocity_covariance{};
  Vec3 linear_acceleration = Vec3::Zero();
  std::array<double, 9> linear_acceleration_covariance{};
};

/// geometry_msgs/Twist.
struct Twist {
  Vec3 linear = Vec3::Zero();
  Vec3 angular = Vec3::Zero();
};

/// nav_msgs/Odometry: pose in header.frame_id, twist in child_frame_id.
struct Odometry {
  Header header;
  std::string child_frame_id;
  Pose3 pose;
  std::array<double, 36> pose_covariance{};
  Twist twist;
  std::array<double, 36> twist_covariance{};
};

/// sensor_msgs/JointState.
struct JointState {
  Header header;
  std::vector<std::string> name;
  std::vector<double> position, velocity, effort;
};

/// geometry_msgs/TransformStamped.
struct TransformStamped {
  Header header;
  std::string child_frame_id;
  Pose3 transform;  ///< pose of child_frame_id in header.frame_id
};

/// tf2_msgs/TFMessage.
struct TFMessage {
  std::vector<TransformStamped> transforms;
};

/// geometry_msgs/PoseStamped.
struct PoseStamped {
  Header header;
  Pose3 pose;
};

/// nav_msgs/Path.
struct Path {
  Header header;
  std::vector<PoseStamped> poses;
};

/// nav_msgs/OccupancyGrid: row-major from the origin, -1 unknown, 0 free .. 100 occupied.
struct OccupancyGrid {
  Header header;
  SimTime map_load_time;
  float resolution = 0.05f;           ///< m per cell
  std::uint32_t width = 0, height = 0;
  Pose3 origin;                       ///< pose of cell (0, 0)'s corner in header.frame_id
  std::vector<std::int8_t> data;
};

/// std_msgs/Float64MultiArray (layout left empty): the common ros2_control habit for joint
/// position commands; used for /head/command.
struct Float64MultiArray {
  std::vector<double> data;
};

/// std_msgs/String: one text, e.g. /robot_description (a robot's URDF).
struct String {
  std::string data;
};

/// std_msgs/Bool: one switch, e.g. /lights (a robot's lamps on or off).
struct Bool {
  bool data = false;
};

/// Bodies touching a robot's chassis (like a bumper), by object name.
struct Contacts {
  Header header;
  std::vector<std::string> touching;
};

/// sensor_msgs/Image.
struct Image {
  Header header;
  std::uint32_t height = 0, width = 0;
  std::string encoding;               ///< rgb8, 32FC1, 16UC1, mono16, mono8
  std::uint8_t is_bigendian = 0;
  std::uint32_t step = 0;             ///< bytes per row
  std::vector<std::uint8_t> data;
};

/// sensor_msgs/CameraInfo (plumb_bob distortion).
struct CameraInfo {
  Header header;
  std::uint32_t height = 0, width = 0;
  std::string distortion_model = "plumb_bob";
  std::vector<double> d;              ///< k1, k2, p1, p2, k3
  std::array<double, 9> k{};
  std::array<double, 9> r{1, 0, 0, 0, 1, 0, 0, 0, 1};
  std::array<double, 12> p{};
  std::uint32_t binning_x = 0, binning_y = 0;
  std::uint32_t roi_x_offset = 0, roi_y_offset = 0, roi_height = 0, roi_width = 0;
  bool roi_do_rectify = false;
};

/// sensor_msgs/PointField.
struct PointField {
  static constexpr std::uint8_t kFloat32 = 7;
  std::string name;
  std::uint32_t offset = 0;
  std::uint8_t datatype = kFloat32;
  std::uint32_t count = 1;
};

/// sensor_msgs/PointCloud2.
struct PointCloud2 {
  Header header;
  std::uint32_t height = 1, width = 0;
  std::vector<PointField> fields;
  bool is_bigendian = false;
  std::uint32_t point_step = 0, row_step = 0;
  std::vector<std::uint8_t> data;
  bool is_dense = false;
};

/// Any message on the Bus. New types go at the end: an alternative's index is part of digests.
using Message = std::variant<Clock, LaserScan, Range, Imu, Twist, Odometry, JointState, TFMessage, PoseStamped, Path,
                             OccupancyGrid, Float64MultiArray, Contacts, Image, CameraInfo, PointCloud2, String, Bool>;

/// The ROS type name of each alternative ("sensor_msgs/LaserScan"); ROS 2 inserts "/msg/".
const char* type_name(const Message& m);
template <class T>
const char* type_name_of();

/// The stamp of a message (its header's, or the clock's), zero for unstamped messages.
SimTime stamp_of(const Message& m);

}  // namespace rescuesim::msg
