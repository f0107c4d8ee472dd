#pragma once
/// Rigid poses in 2D and 3D on Eigen. Names follow the monogram habit: `X_WB` is the pose of
/// frame B measured and expressed in frame W, so `X_WC = X_WB * X_BC`.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

namespace rescuesim {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Quat = Eigen::Quaterniond;

/// Wrap an angle to (-pi, pi].
inline double wrap_angle(double a) {
  a = std::remainder(a, 2.0 * M_PI);
  return a <= -M_PI ? a + 2.0 * M_PI : a;
}

/// A planar pose: position (m) and heading yaw (rad, counter-clockwise from +x).
struct Pose2 {
  double x = 0, y = 0, yaw = 0;

  Vec2 position() const { return {x, y}; }
  /// Maps a point from this pose's frame into the parent frame.
  Vec2 transform(const Vec2& p_B) const {
    const double c = std::cos(yaw), s = std::sin(yaw);
    return {x + c * p_B.x() - s * p_B.y(), y + s * p_B.x() + c * p_B.y()};
  }
  /// X_WC = X_WB * X_BC.
  Pose2 operator*(const Pose2& X_BC) const {
    const Vec2 p = transform(X_BC.position());
    return {p.x(), p.y(), wrap_angle(yaw + X_BC.yaw)};
  }
  Pose2 inverse() const {
    const double c = std::cos(yaw), s = std::sin(yaw);
    return {-(c * x + s * y), -(-s * x + c * y), wrap_angle(-yaw)};
  }
};

/// A rigid pose in 3D: translation (m) and unit quaternion.
struct Pose3 {
  Vec3 p = Vec3::Zero();
  Quat q = Quat::Identity();

  static Pose3 from_pose2(const Pose2& X, double z = 0.0) {
    return {Vec3(X.x, X.y, z), Quat(Eigen::AngleAxisd(X.yaw, Vec3::UnitZ()))};
  }
  static Pose3 from_rpy(const Vec3& p, double roll, double pitch, double yaw) {
    return {p, Quat(Eigen::AngleAxisd(yaw, Vec3::UnitZ()) * Eigen::AngleAxisd(pitch, Vec3::UnitY()) *
                    Eigen::AngleAxisd(roll, Vec3::UnitX()))};
  }
  /// X_WC = X_WB * X_BC.
  Pose3 operator*(const Pose3& X_BC) const { return {p + q * X_BC.p, (q * X_BC.q).normalized()}; }
  /// Maps a point expressed in this frame into the parent frame.
  Vec3 operator*(const Vec3& p_B) const { return p + q * p_B; }
  Pose3 inverse() const {
    const Quat qi = q.conjugate();
    return {-(qi * p), qi};
  }
  /// Heading about +z (rad), from the rotation's x axis projected on the ground plane.
  double yaw() const {
    const Vec3 x = q * Vec3::UnitX();
    return std::atan2(x.y(), x.x());
  }
  Pose2 to_pose2() const { return {p.x(), p.y(), yaw()}; }
  Eigen::Isometry3d isometry() const {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = q.toRotationMatrix();
    T.translation() = p;
    return T;
  }
};

}  // namespace rescuesim
