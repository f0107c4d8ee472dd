// Built only when Debian's ROS 1 message headers are installed (see tests/CMakeLists.txt), as
// C++17. The values repeat samples.h on purpose: the two sides are built independently.

#include "roscpp_reference.h"

#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/Twist.h>
#include <nav_msgs/OccupancyGrid.h>
#include <nav_msgs/Odometry.h>
#include <nav_msgs/Path.h>
#include <ros/serialization.h>
#include <rosgraph_msgs/Clock.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/JointState.h>
#include <sensor_msgs/LaserScan.h>
#include <sensor_msgs/PointCloud2.h>
#include <sensor_msgs/Range.h>
#include <std_msgs/Float64MultiArray.h>
#include <std_msgs/Bool.h>
#include <std_msgs/String.h>
#include <tf2_msgs/TFMessage.h>

#include <limits>

namespace rescuesim::msg::test {

namespace {

template <class M>
RoscppSample serialize(const M& m) {
  RoscppSample s;
  s.known = true;
  const std::uint32_t n = ros::serialization::serializationLength(m);
  s.bytes.resize(n);
  ros::serialization::OStream stream(s.bytes.data(), n);
  ros::serialization::serialize(stream, m);
  s.md5 = ros::message_traits::MD5Sum<M>::value();
  s.datatype = ros::message_traits::DataType<M>::value();
  return s;
}

std_msgs::Header header(std::uint32_t seq, std::uint32_t sec, std::uint32_t nsec, const char* frame) {
  std_msgs::Header h;
  h.seq = seq;
  h.stamp = ros::Time(sec, nsec);
  h.frame_id = frame;
  return h;
}

geometry_msgs::Pose pose(double x, double y, double z, double qx = 0, double qy = 0, double qz = 0, double qw = 1) {
  geometry_msgs::Pose p;
  p.position.x = x;
  p.position.y = y;
  p.position.z = z;
  p.orientation.x = qx;
  p.orientation.y = qy;
  p.orientation.z = qz;
  p.orientation.w = qw;
  return p;
}

}  // namespace

RoscppSample roscpp_sample(const std::string& type, std::uint32_t seq) {
  if (type == "rosgraph_msgs/Clock") {
    rosgraph_msgs::Clock m;
    m.clock = ros::Time(1, 500000000);
    return serialize(m);
  }
  if (type == "sensor_msgs/LaserScan") {
    sensor_msgs::LaserScan m;
    m.header = header(seq, 2, 250000000, "laser");
    m.angle_min = -0.5f;
    m.angle_max = 0.5f;
    m.angle_increment = 1.0f;
    m.time_increment = 0.25f;
    m.scan_time = 0.125f;
    m.range_min = 0.0625f;
    m.range_max = 8.0f;
    m.ranges = {1.5f, std::numeric_limits<float>::infinity()};
    return serialize(m);
  }
  if (type == "sensor_msgs/Range") {
    sensor_msgs::Range m;
    m.header = header(seq, 3, 0, "s");
    m.radiation_type = sensor_msgs::Range::INFRARED;
    m.field_of_view = 0.5f;
    m.min_range = 0.25f;
    m.max_range = 2.0f;
    m.range = 1.0f;
    return serialize(m);
  }
  if (type == "sensor_msgs/Imu") {
    sensor_msgs::Imu m;
    m.header = header(seq, 1, 0, "imu");
    m.orientation.x = 1;
    m.orientation.y = 2;
    m.orientation.z = 3;
    m.orientation.w = 4;
    m.orientation_covariance = {1, 0, 0, 0, 2, 0, 0, 0, 3};
    m.angular_velocity.x = -1;
    m.angular_velocity.z = 1;
    m.angular_velocity_covariance[0] = -1;
    m.linear_acceleration.z = 9.75;
    return serialize(m);
  }
  if (type == "geometry_msgs/Twist") {
    geometry_msgs::Twist m;
    m.linear.x = 0.5;
    m.angular.z = -0.25;
    return serialize(m);
  }
  if (type == "nav_msgs/Odometry") {
    nav_msgs::Odometry m;
    m.header = header(seq, 12, 1, "odom");
    m.child_frame_id = "base_link";
    m.pose.pose = pose(1, 2, 0, 0, 0, -0.5, 0.75);
    m.pose.covariance[0] = 0.5;
    m.pose.covariance[35] = 0.25;
    m.twist.twist.linear.x = 0.5;
    m.twist.twist.angular.z = 0.125;
    m.twist.covariance[0] = 2;
    return serialize(m);
  }
  if (type == "sensor_msgs/JointState") {
    sensor_msgs::JointState m;
    m.header = header(seq, 1, 0, "base_link");
    m.name = {"pan", "tilt"};
    m.position = {0.5, -0.25};
    m.velocity = {1, 2};
    return serialize(m);
  }
  if (type == "tf2_msgs/TFMessage") {
    tf2_msgs::TFMessage m;
    geometry_msgs::TransformStamped t;
    t.header = header(0, 2, 0, "odom");
    t.child_frame_id = "base_link";
    t.transform.translation.x = 1;
    t.transform.translation.y = -1;
    t.transform.rotation.w = 1;
    m.transforms.push_back(t);
    return serialize(m);
  }
  if (type == "geometry_msgs/PoseStamped") {
    geometry_msgs::PoseStamped m;
    m.header = header(seq, 5, 0, "map");
    m.pose = pose(1, 2, 3);
    return serialize(m);
  }
  if (type == "nav_msgs/Path") {
    nav_msgs::Path m;
    m.header = header(seq, 5, 0, "map");
    geometry_msgs::PoseStamped a, b;
    a.header = header(0, 1, 0, "map");
    a.pose = pose(1, 0, 0);
    b.header = header(0, 2, 0, "map");
    b.pose = pose(2, 0, 0, 0, 0, 1, 0);
    m.poses = {a, b};
    return serialize(m);
  }
  if (type == "nav_msgs/OccupancyGrid") {
    nav_msgs::OccupancyGrid m;
    m.header = header(seq, 7, 0, "map");
    m.info.map_load_time = ros::Time(6, 0);
    m.info.resolution = 0.5f;
    m.info.width = 2;
    m.info.height = 1;
    m.info.origin = pose(-1, -2, 0);
    m.data = {-1, 100};
    return serialize(m);
  }
  if (type == "std_msgs/Float64MultiArray") {
    std_msgs::Float64MultiArray m;
    m.data = {1.5, -2.0};
    return serialize(m);
  }
  if (type == "std_msgs/Bool") {
    std_msgs::Bool m;
    m.data = true;
    return serialize(m);
  }
  if (type == "std_msgs/String") {
    std_msgs::String m;
    m.data = "ab";
    return serialize(m);
  }
  if (type == "sensor_msgs/Image") {
    sensor_msgs::Image m;
    m.header = header(seq, 1, 0, "cam");
    m.height = 1;
    m.width = 2;
    m.encoding = "rgb8";
    m.step = 6;
    m.data = {1, 2, 3, 4, 5, 6};
    return serialize(m);
  }
  if (type == "sensor_msgs/CameraInfo") {
    sensor_msgs::CameraInfo m;
    m.header = header(seq, 1, 0, "cam");
    m.height = 480;
    m.width = 640;
    m.distortion_model = "plumb_bob";
    m.D = {0.5, -0.25, 0, 0, 0.125};
    m.K = {500, 0, 320, 0, 500, 240, 0, 0, 1};
    m.R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    m.P = {500, 0, 320, 0, 0, 500, 240, 0, 0, 0, 1, 0};
    m.binning_x = 1;
    m.roi.width = 8;
    m.roi.do_rectify = true;
    return serialize(m);
  }
  if (type == "sensor_msgs/PointCloud2") {
    sensor_msgs::PointCloud2 m;
    m.header = header(seq, 1, 0, "cam");
    m.height = 1;
    m.width = 1;
    for (const auto& [name, offset] : {std::pair<const char*, std::uint32_t>{"x", 0}, {"y", 4}, {"z", 8}}) {
      sensor_msgs::PointField f;
      f.name = name;
      f.offset = offset;
      f.datatype = sensor_msgs::PointField::FLOAT32;
      f.count = 1;
      m.fields.push_back(f);
    }
    m.point_step = 12;
    m.row_step = 12;
    m.data = {0x00, 0x00, 0x80, 0x3f, 0x00, 0x00, 0x00, 0x40, 0x00, 0x00, 0x00, 0xbf};
    m.is_dense = true;
    return serialize(m);
  }
  return {};
}

}  // namespace rescuesim::msg::test
