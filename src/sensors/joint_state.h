#pragma once
/// Joint encoders: every moving joint's position, velocity and effort, as robot_state_publisher
/// and MoveIt expect them on joint_states.

#include "core/sim_time.h"
#include "msgs/messages.h"
#include "world/state.h"
#include "world/world.h"

namespace rescuesim {

/// The joint states of `robot`: one entry per joint that is not fixed, in RobotSpec::joints
/// order, with its name, position q (rad or m), velocity qd (rad/s or m/s) and effort (N·m or N)
/// from State::robots[robot]. Stamped `stamp`, empty frame_id (joint states have no frame).
msg::JointState sample_joint_states(const World& world, const State& state, RobotIndex robot, SimTime stamp);

}  // namespace rescuesim
