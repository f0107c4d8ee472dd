#pragma once
/// The IMU sampler: angular velocity and specific force (acceleration minus gravity, so +9.81
/// m/s^2 up at rest) in the sensor frame, from the mount link's motion; orientation in the
/// world frame; white noise and random-walk biases per axis (biases live in SensorSlot::imu).

#include "msgs/messages.h"
#include "world/state.h"
#include "world/world.h"

namespace rescuesim {

/// Samples an IMU mounted on base link of `robot` (the mount link must be the base link;
/// others are rejected when the simulation is set up). `slot.imu` keeps the biases and the
/// mount point's velocity at the previous sample between calls. The acceleration is the
/// mean over the interval since the previous sample, as a real IMU's integrating filter gives.
msg::Imu sample_imu(const World& world, const State& state, RobotIndex robot, const SensorSpec& spec, SimTime stamp, SensorSlot& slot);

}  // namespace rescuesim
