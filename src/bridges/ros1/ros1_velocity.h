#pragma once
/// cmd_vel over ROS 1 in either type a publisher may use: geometry_msgs/Twist, or
/// geometry_msgs/TwistStamped (what ros2_controllers' diff_drive_controller takes since Jazzy, and
/// what Nav2 publishes by default from Kilted; ROS 1 stacks bridged from ROS 2 send it too). ROS 1
/// gives a topic one type per connection: the bridge subscribes with MD5 and type "*" so that
/// publishers of any type connect, and reads each connection header's `type` and `md5sum` to
/// tell which of the two arrived (velocity_type), then decodes the bytes (decode_velocity).
/// roscpp fixes such a subscription's MD5 to that of the first publisher it connects to, so one
/// type at a time connects; the bridge makes the subscription afresh when no publisher is
/// connected (ros1_bridge.cpp, check_input_publishers).
///
/// geometry_msgs/TwistStamped is not one of msg::Message's types (the Bus never carries it, no
/// topic publishes it), so rather than adding a type to every serialiser for one input, its Header
/// is read here (bounds-checked, like msgs' decoders) and the Twist after it goes to msgs' own
/// ROS 1 decoder. Free of roscpp, so tests check it with bytes worked out by hand.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "core/sim_time.h"
#include "msgs/messages.h"

namespace rescuesim::ros1_wire {

/// ROS 1's MD5 of geometry_msgs/TwistStamped (as `rosmsg md5` prints it): the MD5 of
/// "<MD5 of std_msgs/Header> header\n<MD5 of geometry_msgs/Twist> twist".
inline constexpr const char* kTwistStampedMd5 = "98d34b0043a2093cf9d9345ab6eef12e";
inline constexpr const char* kTwistStampedName = "geometry_msgs/TwistStamped";


/// Which of the two velocity types a connection carries.
enum class VelocityType { twist, twist_stamped };

/// The velocity type named by a connection header's `type` and `md5sum`, or nothing, with `why`
/// set ("a std_msgs/String message: cmd_vel takes geometry_msgs/Twist or geometry_msgs/TwistStamped").
/// The MD5 must be the one ROS 1 computes for the type (another means another definition).
std::optional<VelocityType> velocity_type(std::string_view type, std::string_view md5, std::string* why);

/// A decoded velocity command.
struct VelocityCommand {
  msg::Twist twist;
  bool stamped = false;
  SimTime stamp;         ///< header.stamp (TwistStamped; sec + nsec, zero when unset)
  std::string frame_id;  ///< header.frame_id (TwistStamped)
};

/// Decodes one message of `type` (ROS 1 wire format, without roscpp's 4-byte length). Throws
/// rescuesim::Error naming the type and the field on malformed bytes ("geometry_msgs/TwistStamped:
/// header.stamp.nsec: truncated: a value needs 4 bytes, 2 left"), trailing bytes included.
VelocityCommand decode_velocity(VelocityType type, std::span<const std::uint8_t> bytes);


}  // namespace rescuesim::ros1_wire
