#pragma once
/// A contact (bumper) sensor: the names of the world objects touching any of a robot's links.

#include "core/sim_time.h"
#include "msgs/messages.h"
#include "world/sensor_spec.h"
#include "world/state.h"

namespace rescuesim {

/// What touches `robot` now: State::robots[robot].touching (physics keeps it sorted, each name
/// once), stamped `stamp`, in frame spec.frame_id.
msg::Contacts sample_contacts(const State& state, RobotIndex robot, const SensorSpec& spec, SimTime stamp);

}  // namespace rescuesim
