#pragma once
// Small messages of every type, with values chosen so that hand-written wire bytes stay short
// and checkable (exact binary fractions where possible), and a little-endian byte builder for
// writing expected bytes field by field, independent of the code under test.

#include <bit>
#include <cstdint>
#include <limits>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>

#include "msgs/messages.h"

namespace rescuesim::msg::test {

inline Header header(std::int64_t ns, const char* frame) { return Header{SimTime{ns}, frame}; }
inline Pose3 pose(double x, double y, double z, const Quat& q = Quat::Identity()) { return Pose3{Vec3(x, y, z), q}; }

inline Clock clock_msg() { return Clock{SimTime{1'500'000'000}}; }

inline LaserScan laser_scan() {
  LaserScan m;
  m.header = header(2'250'000'000, "laser");
  m.angle_min = -0.5f;
  m.angle_max = 0.5f;
  m.angle_increment = 1.0f;
  m.time_increment = 0.25f;
  m.scan_time = 0.125f;
  m.range_min = 0.0625f;
  m.range_max = 8.0f;
  m.ranges = {1.5f, std::numeric_limits<float>::infinity()};
  return m;
}

inline Range range_msg() {
  Range m;
  m.header = header(3'000'000'000, "s");
  m.radiation_type = Range::kInfrared;
  m.field_of_view = 0.5f;
  m.min_range = 0.25f;
  m.max_range = 2.0f;
  m.range = 1.0f;
  return m;
}

inline Imu imu() {
  Imu m;
  m.header = header(1'000'000'000, "imu");
  m.orientation = Quat(4, 1, 2, 3);  // Eigen order w, x, y, z: on the wire x=1 y=2 z=3 w=4
  m.orientation_covariance = {1, 0, 0, 0, 2, 0, 0, 0, 3};
  m.angular_velocity = Vec3(-1, 0, 1);
  m.angular_velocity_covariance[0] = -1;
  m.linear_acceleration = Vec3(0, 0, 9.75);
  return m;
}

inline Twist twist() { return Twist{Vec3(0.5, 0, 0), Vec3(0, 0, -0.25)}; }

inline Odometry odometry() {
  Odometry m;
  m.header = header(12'000'000'001, "odom");
  m.child_frame_id = "base_link";
  m.pose = pose(1, 2, 0, Quat(0.75, 0, 0, -0.5));
  m.pose_covariance[0] = 0.5;
  m.pose_covariance[35] = 0.25;
  m.twist = Twist{Vec3(0.5, 0, 0), Vec3(0, 0, 0.125)};
  m.twist_covariance[0] = 2;
  return m;
}

inline JointState joint_state() {
  JointState m;
  m.header = header(1'000'000'000, "base_link");
  m.name = {"pan", "tilt"};
  m.position = {0.5, -0.25};
  m.velocity = {1, 2};
  return m;
}

inline TFMessage tf_message() {
  TransformStamped t;
  t.header = header(2'000'000'000, "odom");
  t.child_frame_id = "base_link";
  t.transform = pose(1, -1, 0);
  return TFMessage{{t}};
}

inline PoseStamped pose_stamped() { return PoseStamped{header(5'000'000'000, "map"), pose(1, 2, 3)}; }

inline Path path() {
  Path m;
  m.header = header(5'000'000'000, "map");
  m.poses = {PoseStamped{header(1'000'000'000, "map"), pose(1, 0, 0)},
             PoseStamped{header(2'000'000'000, "map"), pose(2, 0, 0, Quat(0, 0, 0, 1))}};
  return m;
}

inline OccupancyGrid occupancy_grid() {
  OccupancyGrid m;
  m.header = header(7'000'000'000, "map");
  m.map_load_time = SimTime{6'000'000'000};
  m.resolution = 0.5f;
  m.width = 2;
  m.height = 1;
  m.origin = pose(-1, -2, 0);
  m.data = {-1, 100};
  return m;
}

inline Float64MultiArray float64_multi_array() { return Float64MultiArray{{1.5, -2.0}}; }

inline Contacts contacts() { return Contacts{header(1'000'000'000, "base_link"), {"victim_1"}}; }

inline Image image() {
  Image m;
  m.header = header(1'000'000'000, "cam");
  m.height = 1;
  m.width = 2;
  m.encoding = "rgb8";
  m.step = 6;
  m.data = {1, 2, 3, 4, 5, 6};
  return m;
}

inline CameraInfo camera_info() {
  CameraInfo m;
  m.header = header(1'000'000'000, "cam");
  m.height = 480;
  m.width = 640;
  m.d = {0.5, -0.25, 0, 0, 0.125};
  m.k = {500, 0, 320, 0, 500, 240, 0, 0, 1};
  m.p = {500, 0, 320, 0, 0, 500, 240, 0, 0, 0, 1, 0};
  m.binning_x = 1;
  m.roi_width = 8;
  m.roi_do_rectify = true;
  return m;
}

inline PointCloud2 point_cloud2() {
  PointCloud2 m;
  m.header = header(1'000'000'000, "cam");
  m.height = 1;
  m.width = 1;
  m.fields = {PointField{"x", 0}, PointField{"y", 4}, PointField{"z", 8}};
  m.point_step = 12;
  m.row_step = 12;
  // x=1.0f y=2.0f z=-0.5f as little-endian float32
  m.data = {0x00, 0x00, 0x80, 0x3f, 0x00, 0x00, 0x00, 0x40, 0x00, 0x00, 0x00, 0xbf};
  m.is_dense = true;
  return m;
}

inline String string_msg() { return String{"ab"}; }

inline Bool bool_msg() { return Bool{true}; }

/// One sample of every alternative, in msg::Message order.
inline std::vector<Message> all_samples() {
  return {clock_msg(), laser_scan(),   range_msg(),           imu(),      twist(),         odometry(),
          joint_state(), tf_message(), pose_stamped(),        path(),     occupancy_grid(), float64_multi_array(),
          contacts(),  image(),        camera_info(),         point_cloud2(), string_msg(), bool_msg()};
}

/// Expected bytes, built little endian by shifts (not by the code under test's memcpy).
class Bytes {
 public:
  Bytes& u8(std::uint8_t x) { return put(x, 1); }
  Bytes& i8(std::int8_t x) { return put(static_cast<std::uint8_t>(x), 1); }
  Bytes& u32(std::uint32_t x) { return put(x, 4); }
  Bytes& i32(std::int32_t x) { return put(static_cast<std::uint32_t>(x), 4); }
  Bytes& f32(float x) { return put(std::bit_cast<std::uint32_t>(x), 4); }
  Bytes& f64(double x) { return put(std::bit_cast<std::uint64_t>(x), 8); }
  Bytes& chars(std::string_view s) {
    for (char c : s) b_.push_back(static_cast<std::uint8_t>(c));
    return *this;
  }
  /// ROS 1 string: uint32 length, bytes.
  Bytes& str1(std::string_view s) { return u32(static_cast<std::uint32_t>(s.size())).chars(s); }
  /// CDR string: uint32 length with the NUL, bytes, NUL.
  Bytes& str2(std::string_view s) { return u32(static_cast<std::uint32_t>(s.size() + 1)).chars(s).u8(0); }
  /// `n` zero bytes of CDR alignment padding, written out by hand.
  Bytes& pad(int n) {
    for (int i = 0; i < n; ++i) b_.push_back(0);
    return *this;
  }
  /// Bytes given as hex text ("00 01 00 00").
  Bytes& hex(std::string_view h) {
    for (std::size_t i = 0; i + 1 < h.size() + 1;) {
      while (i < h.size() && h[i] == ' ') ++i;
      if (i >= h.size()) break;
      b_.push_back(static_cast<std::uint8_t>(std::stoi(std::string(h.substr(i, 2)), nullptr, 16)));
      i += 2;
    }
    return *this;
  }
  /// Checks that the next byte is at CDR offset `off` (counted after the 4-byte encapsulation header).
  Bytes& at(std::size_t off) {
    EXPECT_EQ(b_.size() - 4, off) << "hand-computed CDR offset";
    return *this;
  }
  const std::vector<std::uint8_t>& bytes() const { return b_; }

 private:
  Bytes& put(std::uint64_t x, int n) {
    for (int i = 0; i < n; ++i) b_.push_back(static_cast<std::uint8_t>(x >> (8 * i)));
    return *this;
  }
  std::vector<std::uint8_t> b_;
};

}  // namespace rescuesim::msg::test
