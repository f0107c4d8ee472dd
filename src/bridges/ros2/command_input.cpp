#include "bridges/ros2/command_input.h"

#include "bridges/common/cdr_stream.h"
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

Decoded<StampedTwist> decode_twist_stamped(std::span<const std::uint8_t> cdr) {
  try {
    // read in the byte order the encapsulation names, as the transport's own action_msgs are
    cdr::Reader in(cdr, "geometry_msgs/TwistStamped", cdr::Encapsulations::either_endian);
    StampedTwist out;
    std::int32_t sec = 0;
    std::uint32_t nanosec = 0;
    in.value("header.stamp.sec", sec);
    in.value("header.stamp.nanosec", nanosec);
    if (nanosec >= 1'000'000'000u) in.fail("header.stamp.nanosec", std::to_string(nanosec) + " is not below 1e9");
    out.stamp = SimTime{std::int64_t{sec} * 1'000'000'000 + nanosec};
    in.string("header.frame_id", out.frame_id);
    static const char* const kNames[6] = {"twist.linear.x", "twist.linear.y", "twist.linear.z",
                                          "twist.angular.x", "twist.angular.y", "twist.angular.z"};
    for (int i = 0; i < 6; ++i) {
      double v = 0;
      in.value(kNames[i], v);
      (i < 3 ? out.twist.linear : out.twist.angular)[i % 3] = v;
    }
    in.finish();
    return {std::move(out), {}};
  } catch (const Error& e) {
    return {std::nullopt, "malformed CDR: " + e.message()};
  }
}


Decoded<std::vector<double>> decode_head_command(std::span<const std::uint8_t> cdr) {
  auto a = decode<msg::Float64MultiArray>("std_msgs/Float64MultiArray", cdr);
  if (!a.value) return {std::nullopt, std::move(a.problem)};
  return {std::move(a.value->data), {}};
}

Decoded<msg::JointState> decode_joint_command(std::span<const std::uint8_t> cdr) {
  return decode<msg::JointState>("sensor_msgs/JointState", cdr);
}

}  // namespace rescuesim::ros2
