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

#include "core/sim_time.h"
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

/// geometry_msgs/TwistStamped: std_msgs/Header, then the Twist.
struct StampedTwist {
  SimTime stamp;         ///< header.stamp; 0 when the publisher left it unset
  std::string frame_id;  ///< header.frame_id (the drive takes twists in the robot's base frame whatever it says)
  msg::Twist twist;
};
/// geometry_msgs/TwistStamped bytes (XCDR1, either byte order). Up to 3 bytes of padding may
/// follow the message; a stamp whose nanosec is not below 1e9 is malformed.
Decoded<StampedTwist> decode_twist_stamped(std::span<const std::uint8_t> cdr);


/// std_msgs/Float64MultiArray bytes (head/command): the data array.
Decoded<std::vector<double>> decode_head_command(std::span<const std::uint8_t> cdr);
/// sensor_msgs/JointState bytes (joint_command).
Decoded<msg::JointState> decode_joint_command(std::span<const std::uint8_t> cdr);

}  // namespace rescuesim::ros2
