#pragma once
/// Commands arriving from ROS 2 as serialised bytes (XCDR1 with the encapsulation header),
/// decoded before anything reaches the host. Bytes that are not a message of the type are
/// refused here with a reason a user can act on; the values themselves (finite, right length,
/// known joints) are checked by the gate all bridges share (bridges/common/commands.h).

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "msgs/messages.h"

namespace rescuesim::ros2 {

/// A decoded command, or why its bytes did not decode.
template <class T>
struct Decoded {
  std::optional<T> value;
  std::string problem;  ///< empty when `value` is set ("malformed CDR: ...")
};

/// geometry_msgs/Twist bytes.
Decoded<msg::Twist> decode_twist(std::span<const std::uint8_t> cdr);
/// std_msgs/Float64MultiArray bytes (head/command): the data array.
Decoded<std::vector<double>> decode_head_command(std::span<const std::uint8_t> cdr);
/// sensor_msgs/JointState bytes (joint_command).
Decoded<msg::JointState> decode_joint_command(std::span<const std::uint8_t> cdr);

}  // namespace rescuesim::ros2
