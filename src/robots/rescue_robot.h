#pragma once
/// The built-in robot models, as data.

#include <map>
#include <string>

#include "world/robot_spec.h"

namespace rescuesim {

/// The wheeled rescue robot of the jmeSim paper: a 0.60 × 0.40 m skid-steer chassis (about
/// 25 kg with everything) on four driven wheels, a 4-DOF sensor head on a mast (mast yaw,
/// shoulder pitch, elbow pitch, head tilt), a 270° laser at the front, four sonars at the
/// corners, an IMU, wheel odometry, and the head's cameras.
RobotSpec rescue_robot();

/// Every built-in model by name ("rescue_robot", "tracked_robot").
std::map<std::string, RobotSpec> builtin_models();

}  // namespace rescuesim
