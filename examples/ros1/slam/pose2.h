#pragma once
/// Planar poses for the SLAM demonstration's ROS nodes (C++17: they include Debian's roscpp
/// message headers, which do not compile as C++20): composition, inverse, interpolation, and
/// conversions from and to ROS quaternions. Frames in names as in the rest of rescuesim:
/// X_AB is the pose of frame B in frame A.

#include <cmath>

#include <geometry_msgs/Quaternion.h>

namespace slam_demo {

/// A pose in the plane: position (m) and heading (rad, counter-clockwise from x).
struct Pose2 {
  double x = 0, y = 0, yaw = 0;
};

/// The angle wrapped into (-pi, pi].
inline double wrap_angle(double a) {
  a = std::remainder(a, 2 * M_PI);
  return a <= -M_PI ? a + 2 * M_PI : a;
}

/// X_AC = X_AB * X_BC.
inline Pose2 compose(const Pose2& X_AB, const Pose2& X_BC) {
  const double c = std::cos(X_AB.yaw), s = std::sin(X_AB.yaw);
  return {X_AB.x + c * X_BC.x - s * X_BC.y, X_AB.y + s * X_BC.x + c * X_BC.y, wrap_angle(X_AB.yaw + X_BC.yaw)};
}

/// X_BA from X_AB.
inline Pose2 inverse(const Pose2& X_AB) {
  const double c = std::cos(X_AB.yaw), s = std::sin(X_AB.yaw);
  return {-c * X_AB.x - s * X_AB.y, s * X_AB.x - c * X_AB.y, wrap_angle(-X_AB.yaw)};
}

/// The pose a fraction f in [0, 1] of the way from a to b (shortest way round for the heading).
inline Pose2 interpolate(const Pose2& a, const Pose2& b, double f) {
  return {a.x + f * (b.x - a.x), a.y + f * (b.y - a.y), wrap_angle(a.yaw + f * wrap_angle(b.yaw - a.yaw))};
}

/// Heading (rotation about z) of a ROS quaternion.
inline double yaw_of(const geometry_msgs::Quaternion& q) {
  return std::atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z));
}

/// A ROS quaternion for a rotation about z.
inline geometry_msgs::Quaternion quaternion_of(double yaw) {
  geometry_msgs::Quaternion q;
  q.z = std::sin(yaw / 2);
  q.w = std::cos(yaw / 2);
  return q;
}

}  // namespace slam_demo
