#include "robots/drive_controller.h"

#include <algorithm>
#include <cmath>

namespace rescuesim {

namespace {
/// The most the yaw-rate integral adds: this times the set turn rate, and at least kHoldTurn
/// (rad/s), which holds a straight line.
constexpr double kTurnAuthority = 3.0, kHoldTurn = 0.2;

double approach(double current, double target, double max_step) {
  return current + std::clamp(target - current, -max_step, max_step);
}
}  // namespace

void update_drive(const RobotSpec& spec, RobotState& s, SimTime now, double dt) {
  const DriveSpec& d = spec.drive;
  // the command in force: none, or too old, means stop
  double v = 0, w_cmd = 0;
  const bool fresh = s.cmd_time.ns >= 0 && (now - s.cmd_time).seconds() <= d.command_timeout;
  if (fresh) {
    v = std::clamp(s.cmd_linear.x(), -d.max_linear, d.max_linear);
    w_cmd = std::clamp(s.cmd_angular.z(), -d.max_angular, d.max_angular);
  }
  s.drive_v = approach(s.drive_v, v, d.max_linear_accel * dt);
  s.drive_w = approach(s.drive_w, w_cmd, d.max_angular_accel * dt);
  if (s.joint_target.size() != spec.joints.size()) s.joint_target.assign(spec.joints.size(), 0.0);
  // at rest the wheels are held where they stopped (a brake), not merely told to turn at zero
  const bool at_rest = v == 0 && w_cmd == 0 && s.drive_v == 0 && s.drive_w == 0 && d.brake_gain > 0 &&
                       s.q.size() == spec.joints.size();
  if (at_rest) {
    if (!s.braking) {
      s.brake_q = s.q;
      s.braking = true;
      s.yaw_rate_integral = 0;
    }
    for (const auto* wheels : {&d.left_wheels, &d.right_wheels}) {
      for (const auto& name : *wheels) {
        const auto j = static_cast<std::size_t>(spec.joint_index(name));
        s.joint_target[j] = d.brake_gain * (s.brake_q[j] - s.q[j]);
      }
    }
    return;
  }
  s.braking = false;
  // yaw-rate feedback: the chassis' measured turn rate (about its own z axis) against the set point
  const double measured_w = (s.base.X_WB.q.conjugate() * s.base.w_WB).z();
  const double error = s.drive_w - measured_w;
  // anti-windup: the integral may add at most three times the turn rate set now (a skid-steer
  // base turning in place needs about twice its set rate in wheel speed difference), and
  // 0.2 rad/s to hold a straight line. A robot that cannot turn (wedged on a post, against a
  // wall) otherwise winds it up until its tracks or wheels counter-rotate at their limit and stay
  // there whatever it is told next, backing up straight included (the old bound, 0.5 rad, was
  // 10 rad/s at ki = 20/s)
  const double bound = d.yaw_rate_ki > 0 ? std::max(kTurnAuthority * std::abs(s.drive_w), kHoldTurn) / d.yaw_rate_ki : 0.0;
  s.yaw_rate_integral = std::clamp(s.yaw_rate_integral + error * dt, -bound, bound);
  const double w = s.drive_w + d.yaw_rate_kp * error + d.yaw_rate_ki * s.yaw_rate_integral;
  // differential kinematics with the effective (slip-corrected) track
  const double half_track = 0.5 * d.track_width * d.track_multiplier;
  const double left = (s.drive_v - w * half_track) / d.wheel_radius;
  const double right = (s.drive_v + w * half_track) / d.wheel_radius;
  for (std::size_t i = 0; i < d.left_wheels.size(); ++i) {
    s.joint_target[static_cast<std::size_t>(spec.joint_index(d.left_wheels[i]))] = wheel_sign(d.left_signs, i) * left;
  }
  for (std::size_t i = 0; i < d.right_wheels.size(); ++i) {
    s.joint_target[static_cast<std::size_t>(spec.joint_index(d.right_wheels[i]))] = wheel_sign(d.right_signs, i) * right;
  }
}

void update_head(const RobotSpec& spec, RobotState& s) {
  if (s.joint_target.size() != spec.joints.size()) s.joint_target.assign(spec.joints.size(), 0.0);
  for (std::size_t i = 0; i < spec.head_joints.size() && i < s.head_target.size(); ++i) {
    const int j = spec.joint_index(spec.head_joints[i]);
    if (j < 0) continue;
    const JointSpec& js = spec.joints[static_cast<std::size_t>(j)];
    s.joint_target[static_cast<std::size_t>(j)] = std::clamp(s.head_target[i], js.lower, js.upper);
  }
  // mimic joints follow their leader (URDF <mimic>): q = multiplier x q_leader + offset
  for (std::size_t j = 0; j < spec.joints.size(); ++j) {
    const JointSpec& js = spec.joints[j];
    if (js.mimic.empty() || js.control != JointSpec::Control::position) continue;
    const int leader = spec.joint_index(js.mimic);
    if (leader < 0 || static_cast<std::size_t>(leader) >= s.q.size()) continue;
    s.joint_target[j] = js.mimic_multiplier * s.q[static_cast<std::size_t>(leader)] + js.mimic_offset;
  }
}

}  // namespace rescuesim
