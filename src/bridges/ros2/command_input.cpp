#include "bridges/ros2/command_input.h"

#include <cmath>

#include "core/error.h"
#include "msgs/serialize.h"

namespace rescuesim::ros2 {

namespace {

template <class T>
Checked<T> refuse(std::string why, bool malformed = false) {
  return {std::nullopt, std::move(why), malformed};
}

/// The first non-finite component's name ("linear.x is nan"), or "".
std::string non_finite(const char* name, const Vec3& v) {
  static const char* const axes[3] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(v[i])) return std::string(name) + "." + axes[i] + " is " + std::to_string(v[i]);
  }
  return {};
}

}  // namespace

Checked<msg::Twist> check_twist(std::span<const std::uint8_t> cdr) {
  static const msg::TypeSupport& type = *msg::find_type("geometry_msgs/Twist");
  msg::Twist twist;
  try {
    twist = std::get<msg::Twist>(msg::from_cdr(type, cdr));
  } catch (const Error& e) {
    return refuse<msg::Twist>("malformed CDR: " + e.message(), true);
  }
  for (const std::string& bad : {non_finite("linear", twist.linear), non_finite("angular", twist.angular)}) {
    if (!bad.empty()) return refuse<msg::Twist>(bad);
  }
  return {twist, {}, false};
}

Checked<std::vector<double>> check_head_command(std::span<const std::uint8_t> cdr, std::size_t joints) {
  static const msg::TypeSupport& type = *msg::find_type("std_msgs/Float64MultiArray");
  std::vector<double> data;
  try {
    data = std::get<msg::Float64MultiArray>(msg::from_cdr(type, cdr)).data;
  } catch (const Error& e) {
    return refuse<std::vector<double>>("malformed CDR: " + e.message(), true);
  }
  if (data.size() != joints) {
    return refuse<std::vector<double>>("data has " + std::to_string(data.size()) + " values, expected " +
                                       std::to_string(joints) + " (one per head joint)");
  }
  for (std::size_t i = 0; i < data.size(); ++i) {
    if (!std::isfinite(data[i])) return refuse<std::vector<double>>("data[" + std::to_string(i) + "] is " + std::to_string(data[i]));
  }
  return {std::move(data), {}, false};
}

Checked<msg::JointState> decode_joint_command(std::span<const std::uint8_t> cdr) {
  static const msg::TypeSupport& type = *msg::find_type("sensor_msgs/JointState");
  try {
    return {std::get<msg::JointState>(msg::from_cdr(type, cdr)), {}, false};
  } catch (const Error& e) {
    return refuse<msg::JointState>("malformed CDR: " + e.message(), true);
  }
}

}  // namespace rescuesim::ros2
