#include "bridges/ros2/command_input.h"

#include "core/error.h"
#include "msgs/serialize.h"

namespace rescuesim::ros2 {

namespace {

/// The message of ROS 1 type `type` in `cdr`, or why the bytes are not one.
template <class T>
Decoded<T> decode(const char* type_name, std::span<const std::uint8_t> cdr) {
  static const msg::TypeSupport& type = *msg::find_type(type_name);
  try {
    return {std::get<T>(msg::from_cdr(type, cdr)), {}};
  } catch (const Error& e) {
    return {std::nullopt, "malformed CDR: " + e.message()};
  }
}

}  // namespace

Decoded<msg::Twist> decode_twist(std::span<const std::uint8_t> cdr) { return decode<msg::Twist>("geometry_msgs/Twist", cdr); }

Decoded<std::vector<double>> decode_head_command(std::span<const std::uint8_t> cdr) {
  auto a = decode<msg::Float64MultiArray>("std_msgs/Float64MultiArray", cdr);
  if (!a.value) return {std::nullopt, std::move(a.problem)};
  return {std::move(a.value->data), {}};
}

Decoded<msg::JointState> decode_joint_command(std::span<const std::uint8_t> cdr) { return decode<msg::JointState>("sensor_msgs/JointState", cdr); }

}  // namespace rescuesim::ros2
