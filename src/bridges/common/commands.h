#pragma once
/// The one gate between commands from the network and the host, shared by the ROS 1, ROS 2 and
/// Foxglove bridges: a decoded cmd_vel, head command or joint command is checked (finite, right
/// length, known joints), counted, and handed to the BridgeHost, which applies it at the next
/// step boundary. Refused commands and values the robot will clamp are reported as warnings
/// naming the topic and the value, worded alike for every transport, at most one per topic and
/// kind every 2 s (with a count of what was held back). Thread-safe: transports call it from
/// their own threads. Decoding the bytes is the transport's (each has its own wire format);
/// bytes that do not decode go to malformed().

#include <atomic>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "core/throttle.h"
#include "msgs/messages.h"
#include "bus/bridge_host.h"

namespace rescuesim {

/// Why a twist may not be applied ("linear.x is nan (...)"), or "" when every component is finite.
std::string twist_problem(const msg::Twist& twist);
/// How far ahead of sim time a stamped velocity command (geometry_msgs/TwistStamped) may be.
/// A publisher on sim time stamps from /clock, which never runs ahead of the simulation, so it
/// needs no slack; 0.5 s (diff_drive_controller's default cmd_vel_timeout, the other way round)
/// leaves room for one that extrapolates between /clock messages and still refuses what the
/// check is for: stamps from the wall clock (some 1.7e9 s) and garbage.
inline constexpr SimTime kFutureStampTolerance = SimTime::from_ms(500);
/// Why a velocity command stamped `stamp` may not be applied at sim time `now`, or "" when it
/// may: a stamp of zero (unset), in the past, or at most kFutureStampTolerance ahead is taken.
std::string stamp_problem(SimTime stamp, SimTime now);
/// Why head targets may not be applied (wrong count for `spec.head_joints`, a non-finite value),
/// or "" when they may.
std::string head_problem(const RobotSpec& spec, const std::vector<double>& positions);

/// See the file comment. Each call returns whether the command was taken and, if not, why (the
/// text of the warning, which Foxglove also sends back to its client).
class CommandGate {
 public:
  /// `source` starts every warning, e.g. "ROS 1".
  CommandGate(BridgeHost& host, std::string source);

  /// cmd_vel (m/s, rad/s in the robot's base frame) for `robot`, received on `topic`. Refused
  /// when a component is not finite; speeds beyond the drive's max_linear / max_angular are
  /// accepted and clamped by the drive, with a warning.
  CommandOutcome velocity(RobotIndex robot, const std::string& topic, const msg::Twist& twist);
  /// A stamped cmd_vel (TwistStamped) at the transport's latest sim time `now`: refused when its
  /// stamp is ahead of `now` (stamp_problem), else as velocity().
  CommandOutcome velocity_stamped(RobotIndex robot, const std::string& topic, SimTime stamp, SimTime now, const msg::Twist& twist);
  /// Head joint targets (rad), one per RobotSpec::head_joints entry, in that order. Refused for
  /// a wrong count or a non-finite value; targets beyond a joint's limits are clamped by the
  /// head controller, with a warning.
  CommandOutcome head(RobotIndex robot, const std::string& topic, const std::vector<double>& positions);
  /// Targets for commandable joints by name (sensor_msgs/JointState on joint_command). Refused
  /// when the host says so (an unknown or uncommandable joint, a missing or non-finite value,
  /// arrays of the wrong length); position targets beyond a joint's limits are clamped, with a
  /// warning.
  CommandOutcome joints(RobotIndex robot, const std::string& topic, const msg::JointState& command);
  /// Flipper targets (rad), one per RobotSpec::flipper_joints entry, in that order
  /// (std_msgs/Float64MultiArray on flippers/command): a joint command for those joints, so
  /// refused for a wrong count or a non-finite value and clamped to the limits with a warning.
  CommandOutcome flippers(RobotIndex robot, const std::string& topic, const std::vector<double>& positions);
  /// A message for the host's inputs()[index] (a mission's report, datagram or relay drop),
  /// received on `topic`; the host checks its content when it hands it over.
  CommandOutcome input(std::size_t index, const std::string& topic, const msg::Message& message);
  /// Bytes on `topic` that did not decode (`why` says where); counted as rejected.
  void malformed(const std::string& topic, const std::string& why);

  std::uint64_t received() const { return received_.load(); }
  std::uint64_t rejected() const { return rejected_.load(); }

 private:
  /// Counts a refused command and warns (throttled per topic and `kind` of problem).
  CommandOutcome reject(const std::string& topic, const char* kind, const std::string& why);
  void warn(const std::string& key, const std::string& text);

  BridgeHost& host_;
  std::string source_;
  std::mutex mutex_;
  std::map<std::string, Throttle> throttles_;  ///< by topic + kind of warning
  std::atomic<std::uint64_t> received_{0}, rejected_{0};
};

}  // namespace rescuesim
