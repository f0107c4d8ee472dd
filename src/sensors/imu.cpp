#include "sensors/imu.h"

#include <cmath>

#include "sensors/noise.h"

namespace rescuesim {

msg::Imu sample_imu(const World& world, const State& state, RobotIndex robot, const SensorSpec& spec, SimTime stamp, SensorSlot& slot) {
  const RobotState& rs = state.robot(robot);
  const ImuSpec& imu = spec.imu;
  Rng& rng = slot.rng;
  const Pose3 X_WS = rs.base.X_WB * spec.X_LS;
  const Quat R_SW = X_WS.q.conjugate();

  // kinematics of the mount point: v_S = v_B + w x r, acceleration by differencing over the interval
  const Vec3 r_W = rs.base.X_WB.q * spec.X_LS.p;
  const Vec3 v_S = rs.base.v_WB + rs.base.w_WB.cross(r_W);
  const double dt = slot.last_sample.ns >= 0 ? (stamp - slot.last_sample).seconds() : 0.0;
  const Vec3 a_W = dt > 0 ? Vec3((v_S - slot.imu.v_WS) / dt) : Vec3::Zero();
  slot.imu.v_WS = v_S;
  // an accelerometer measures acceleration minus gravity: at rest it reads +g upward
  const Vec3 f_S = R_SW * (a_W + Vec3(0, 0, world.gravity));
  const Vec3 w_S = R_SW * rs.base.w_WB;

  // biases walk between samples, then white noise on top
  Vec3& gyro_bias = slot.imu.gyro_bias;
  Vec3& accel_bias = slot.imu.accel_bias;
  if (slot.last_sample.ns < 0) {
    gyro_bias = Vec3::Constant(imu.gyro.bias);
    accel_bias = Vec3::Constant(imu.accel.bias);
  }
  msg::Imu m;
  m.header = {stamp, spec.frame_id};
  for (int i = 0; i < 3; ++i) {
    gyro_bias[i] = walk_bias(gyro_bias[i], imu.gyro, dt, rng);
    accel_bias[i] = walk_bias(accel_bias[i], imu.accel, dt, rng);
    m.angular_velocity[i] = add_noise(w_S[i], imu.gyro, gyro_bias[i], rng);
    m.linear_acceleration[i] = add_noise(f_S[i], imu.accel, accel_bias[i], rng);
  }
  Quat q = X_WS.q;
  if (imu.orientation.stddev > 0) {
    const Vec3 e(rng.normal(0, imu.orientation.stddev), rng.normal(0, imu.orientation.stddev), rng.normal(0, imu.orientation.stddev));
    q = (q * Quat(Eigen::AngleAxisd(e.norm(), e.norm() > 0 ? Vec3(e.normalized()) : Vec3::UnitZ()))).normalized();
  }
  m.orientation = q;
  // diagonal covariances from the white noise
  for (int i = 0; i < 3; ++i) {
    m.orientation_covariance[static_cast<std::size_t>(4 * i)] = imu.orientation.stddev * imu.orientation.stddev;
    m.angular_velocity_covariance[static_cast<std::size_t>(4 * i)] = imu.gyro.stddev * imu.gyro.stddev;
    m.linear_acceleration_covariance[static_cast<std::size_t>(4 * i)] = imu.accel.stddev * imu.accel.stddev;
  }
  slot.last_sample = stamp;
  return m;
}

}  // namespace rescuesim
