#pragma once
/// The gate between commands from the network and the simulation: a decoded cmd_vel, head
/// command or joint command is checked (finite, right length, known joints), counted, and handed
/// to Simulation, which applies it at the next step boundary. Refused commands and values the robot will clamp are reported
/// as warnings naming the topic and the value, at most one per topic and kind every 2 s (with a
/// count of what was held back). Thread-safe: transports call it from their own threads.

#include <atomic>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "msgs/messages.h"
#include "sim/bridge.h"

namespace rescuesim {

class Simulation;

class CommandGate {
 public:
  /// `source` starts every warning, e.g. "ROS 1".
  CommandGate(Simulation& sim, std::string source);

  /// cmd_vel (m/s, rad/s in the robot's base frame) for `robot`, received on `topic`. Returns
  /// false when refused (a non-finite component). Speeds beyond the drive's max_linear /
  /// max_angular are accepted and clamped by the drive, with a warning.
  bool velocity(int robot, const std::string& topic, const msg::Twist& twist);
  /// Head joint targets (rad), one per RobotSpec::head_joints entry, in that order. Returns false
  /// when refused (wrong count, non-finite); targets beyond a joint's limits are clamped by the
  /// head controller, with a warning.
  bool head(int robot, const std::string& topic, const std::vector<double>& positions);
  /// Targets for commandable joints by name (sensor_msgs/JointState on joint_command). Returns
  /// false when refused (Simulation::command_joints says why: an unknown or uncommandable joint, a
  /// missing or non-finite value, arrays of the wrong length); position targets beyond a joint's
  /// limits are clamped, with a warning.
  bool joints(int robot, const std::string& topic, const msg::JointState& command);
  /// Bytes on `topic` that did not decode (`why` says where); counted as rejected.
  void malformed(const std::string& topic, const std::string& why);

  std::uint64_t received() const { return received_.load(); }
  std::uint64_t rejected() const { return rejected_.load(); }

 private:
  /// Counts a refused command and warns (throttled per topic and `kind` of problem).
  void reject(const std::string& topic, const char* kind, const std::string& why);
  void warn(const std::string& key, const std::string& text);

  Simulation& sim_;
  std::string source_;
  std::mutex mutex_;
  std::map<std::string, Throttle> throttles_;  ///< by topic + kind of warning
  std::atomic<std::uint64_t> received_{0}, rejected_{0};
};

}  // namespace rescuesim
