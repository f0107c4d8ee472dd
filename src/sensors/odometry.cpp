#include "sensors/odometry.h"

#include <cmath>

#include "sensors/noise.h"

namespace rescuesim {

namespace {

/// m/s: wheel rims slower than this count as standing (the brake holds them well below it)
constexpr double kStandingWheelSpeed = 1e-3;

/// Body speed (m/s, rad/s) implied by wheel joint velocities under the drive geometry.
struct BodyRate {
  double v = 0, w = 0;
};

BodyRate wheel_odometry_rate(const RobotSpec& spec, const std::vector<double>& qd) {
  const DriveSpec& d = spec.drive;
  auto mean = [&](const std::vector<std::string>& names, const std::vector<double>& signs) {
    double sum = 0;
    for (std::size_t i = 0; i < names.size(); ++i) sum += wheel_sign(signs, i) * qd[static_cast<std::size_t>(spec.joint_index(names[i]))];
    return names.empty() ? 0.0 : sum / static_cast<double>(names.size());
  };
  const double l = mean(d.left_wheels, d.left_signs) * d.wheel_radius, r = mean(d.right_wheels, d.right_signs) * d.wheel_radius;
  return {0.5 * (l + r), (r - l) / (d.track_width * d.track_multiplier)};
}

}  // namespace

void integrate_odometry(const World& world, State& state, RobotIndex robot, const SensorSpec& spec, double dt, SensorSlot& slot) {
  const RobotSpec& rspec = world.robot(robot).spec;
  RobotState& rs = state.robot(robot);
  std::vector<double> qd = rs.qd;
  // encoders are imperfect: each wheel's speed off by a small relative error
  if (spec.odometry.wheel_noise.stddev > 0) {
    for (const auto* side : {&rspec.drive.left_wheels, &rspec.drive.right_wheels}) {
      for (const auto& name : *side) {
        const auto j = static_cast<std::size_t>(rspec.joint_index(name));
        qd[j] *= 1.0 + slot.rng.normal(0.0, spec.odometry.wheel_noise.stddev);
      }
    }
  }
  BodyRate rate = wheel_odometry_rate(rspec, qd);
  if (spec.odometry.gyro_heading) {
    // the chassis gyro's yaw rate, with its own white noise and drifting bias (kept in slot.odometry)
    const double true_rate = (rs.base.X_WB.q.conjugate() * rs.base.w_WB).z();
    double& bias = slot.odometry.gyro_bias;
    bias = walk_bias(bias, spec.odometry.gyro, dt, slot.rng);
    rate.w = add_noise(true_rate, spec.odometry.gyro, bias, slot.rng);
    // a zero-velocity update, as bases that fuse a gyro do: wheels standing still (the drive
    // brakes them at rest) mean the robot is not turning, so the gyro's bias and noise are not
    // integrated into the heading while it stands
    bool standing = !rspec.drive.left_wheels.empty() || !rspec.drive.right_wheels.empty();
    for (const auto* side : {&rspec.drive.left_wheels, &rspec.drive.right_wheels}) {
      for (const auto& name : *side) {
        standing =
            standing && std::abs(rs.qd[static_cast<std::size_t>(rspec.joint_index(name))] * rspec.drive.wheel_radius) < kStandingWheelSpeed;
      }
    }
    if (standing) rate.w = 0;
  }
  // midpoint integration of the unicycle model
  const double yaw_mid = rs.odom.yaw + 0.5 * rate.w * dt;
  rs.odom.x += rate.v * std::cos(yaw_mid) * dt;
  rs.odom.y += rate.v * std::sin(yaw_mid) * dt;
  rs.odom.yaw = wrap_angle(rs.odom.yaw + rate.w * dt);
  rs.odom_v = rate.v;
  rs.odom_w = rate.w;
}

msg::Odometry odometry_message(const World&, const State& state, RobotIndex robot, const SensorSpec& spec, SimTime stamp,
                               const std::string& base_frame) {
  const RobotState& rs = state.robot(robot);
  msg::Odometry m;
  m.header = {stamp, spec.frame_id};
  m.child_frame_id = base_frame;
  m.pose = Pose3::from_pose2(rs.odom);
  m.twist.linear = Vec3(rs.odom_v, 0, 0);
  m.twist.angular = Vec3(0, 0, rs.odom_w);
  // planar odometry: x, y, yaw uncertain, the rest pinned
  const double big = 1e6;
  m.pose_covariance = {0.01, 0, 0, 0, 0, 0, 0, 0.01, 0, 0, 0, 0, 0, 0, big, 0, 0, 0,
                       0,    0, 0, big, 0, 0, 0, 0,    0, 0, big, 0, 0, 0, 0, 0, 0, 0.02};
  m.twist_covariance = {0.001, 0, 0, 0, 0, 0, 0, 0.001, 0, 0, 0, 0, 0, 0, big, 0, 0, 0,
                        0,     0, 0, big, 0, 0, 0, 0,     0, 0, big, 0, 0, 0, 0, 0, 0, 0.005};
  return m;
}

}  // namespace rescuesim
