#pragma once
/// Wheel odometry: dead reckoning from wheel joint velocities and the drive geometry, not from
/// ground truth, so it drifts with skid and slip like a real robot's.

#include "msgs/messages.h"
#include "world/state.h"
#include "world/world.h"

namespace rescuesim {

/// Advances the odometry pose of `robot` by one step of `dt` seconds from its wheel joint
/// velocities (with the spec's relative wheel-speed noise drawn from `slot.rng`; a heading gyro's
/// bias lives in `slot.odometry`).
void integrate_odometry(const World& world, State& state, RobotIndex robot, const SensorSpec& spec, double dt, SensorSlot& slot);

/// The odometry message: pose of base_link in odom, twist in base_link.
msg::Odometry odometry_message(const World& world, const State& state, RobotIndex robot, const SensorSpec& spec, SimTime stamp,
                               const std::string& base_frame);

}  // namespace rescuesim
