#pragma once
/// Controllers that turn commands into joint targets: skid-steer drive (cmd_vel → wheel
/// velocities with speed and acceleration limits and a command timeout) and the head (joint
/// position targets clamped to limits). Pure functions of (RobotSpec, RobotState).

#include "core/sim_time.h"
#include "world/robot_spec.h"
#include "world/state.h"

namespace rescuesim {

/// Sets each wheel joint's velocity target (rad/s) from the robot's last cmd_vel, limited in
/// speed and acceleration over `dt` seconds; a command older than the drive's timeout (or none)
/// brings the robot to a stop, like a real base controller. Stopped (no command in force, set
/// points at zero) it brakes: the wheels are held at the angles where they stopped
/// (DriveSpec::brake_gain), until the next non-zero command.
void update_drive(const RobotSpec& spec, RobotState& state, SimTime now, double dt);

/// Sets the position targets of the head joints from state.head_target, clamped to limits.
void update_head(const RobotSpec& spec, RobotState& state);

}  // namespace rescuesim
