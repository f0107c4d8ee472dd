#pragma once
/// Commands arriving from ROS 2 as serialised bytes (XCDR1 with the encapsulation header),
/// decoded and checked before anything reaches the simulation: malformed bytes, non-finite
/// values and wrong lengths are refused with a reason a user can act on.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "msgs/messages.h"

namespace rescuesim::ros2 {

/// A decoded command, or why it was refused.
template <class T>
struct Checked {
  std::optional<T> value;
  std::string problem;     ///< empty when `value` is set
  bool malformed = false;  ///< the bytes were not a message of the type (else: its values were refused)
};

/// geometry_msgs/Twist bytes: every component must be finite.
Checked<msg::Twist> check_twist(std::span<const std::uint8_t> cdr);

/// std_msgs/Float64MultiArray bytes: exactly `joints` finite positions (rad).
Checked<std::vector<double>> check_head_command(std::span<const std::uint8_t> cdr, std::size_t joints);

/// sensor_msgs/JointState bytes (joint_command): decoded only; which names and values a robot
/// takes is Simulation::command_joints's to check.
Checked<msg::JointState> decode_joint_command(std::span<const std::uint8_t> cdr);

}  // namespace rescuesim::ros2
