#include "bridges/common/commands.h"

#include <cmath>
#include <numbers>

#include "core/log.h"
#include "bus/bridge_host.h"

namespace rescuesim {

namespace {

constexpr double kDeg = 180.0 / std::numbers::pi;

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

}  // namespace

CommandGate::CommandGate(BridgeHost& host, std::string source) : host_(host), source_(std::move(source)) {}

void CommandGate::warn(const std::string& key, const std::string& text) {
  Throttle* throttle = nullptr;
  {
    std::lock_guard lock(mutex_);
    throttle = &throttles_.try_emplace(key).first->second;  // map nodes never move
  }
  std::uint64_t held = 0;
  if (!throttle->allow(&held)) return;
  if (held > 0) {
    log::warn("{}: {} ({} more like it since the last report)", source_, text, held);
  } else {
    log::warn("{}: {}", source_, text);
  }
}

CommandOutcome CommandGate::reject(const std::string& topic, const char* kind, const std::string& why) {
  ++rejected_;
  warn(topic + "#" + kind, "rejected a command on " + topic + ": " + why);
  return CommandOutcome::refused(why);
}

void CommandGate::malformed(const std::string& topic, const std::string& why) { reject(topic, "malformed", "malformed message: " + why); }

std::string twist_problem(const msg::Twist& t) {
  // every component must be finite, even those a planar drive ignores
  static const char* const kNames[6] = {"linear.x", "linear.y", "linear.z", "angular.x", "angular.y", "angular.z"};
  for (int i = 0; i < 6; ++i) {
    const double v = i < 3 ? t.linear[i] : t.angular[i - 3];
    if (!std::isfinite(v)) {
      return fmt::format("{} is {} (geometry_msgs/Twist values must be finite; the robot keeps its last command)", kNames[i], v);
    }
  }
  return {};
}

std::string head_problem(const RobotSpec& spec, const std::vector<double>& positions) {
  if (positions.size() != spec.head_joints.size()) {
    return fmt::format("{} positions, expected {} (rad, in the order {})", positions.size(), spec.head_joints.size(),
                       joined(spec.head_joints));
  }
  for (std::size_t i = 0; i < positions.size(); ++i) {
    if (!std::isfinite(positions[i])) {
      return fmt::format("data[{}] ({}) is {} (positions must be finite)", i, spec.head_joints[i], positions[i]);
    }
  }
  return {};
}

std::string stamp_problem(SimTime stamp, SimTime now) {
  if (stamp.ns == 0 || stamp.ns <= now.ns + kFutureStampTolerance.ns) return {};
  return fmt::format(
      "header.stamp {:.3f} s is {:.3f} s ahead of the simulation's time {:.3f} s (at most {:g} s is allowed; a publisher on "
      "wall-clock time? nodes with use_sim_time stamp with sim time, or leave the stamp 0); the robot keeps its last command",
      stamp.seconds(), (stamp - now).seconds(), now.seconds(), kFutureStampTolerance.seconds());
}

CommandOutcome CommandGate::velocity_stamped(RobotIndex robot, const std::string& topic, SimTime stamp, SimTime now,
                                             const msg::Twist& twist) {
  if (const std::string problem = stamp_problem(stamp, now); !problem.empty()) return reject(topic, "stamp", problem);
  return velocity(robot, topic, twist);
}

CommandOutcome CommandGate::velocity(RobotIndex robot, const std::string& topic, const msg::Twist& t) {
  if (const std::string problem = twist_problem(t); !problem.empty()) return reject(topic, "finite", problem);
  const DriveSpec& d = host_.world().robots.at(robot.slot()).spec.drive;
  if (std::abs(t.linear.x()) > d.max_linear) {
    warn(topic + "#linear", fmt::format("{} linear.x = {:g} m/s is beyond the robot's max_linear: clamped to {:g} m/s", topic, t.linear.x(),
                                        std::copysign(d.max_linear, t.linear.x())));
  }
  if (std::abs(t.angular.z()) > d.max_angular) {
    warn(topic + "#angular", fmt::format("{} angular.z = {:g} rad/s is beyond the robot's max_angular: clamped to {:g} rad/s", topic,
                                         t.angular.z(), std::copysign(d.max_angular, t.angular.z())));
  }
  if (const CommandOutcome r = host_.command_velocity(robot, t); !r) return reject(topic, "refused", "refused by the host: " + r.reason);
  ++received_;
  return CommandOutcome::ok();
}

CommandOutcome CommandGate::head(RobotIndex robot, const std::string& topic, const std::vector<double>& positions) {
  const RobotSpec& spec = host_.world().robots.at(robot.slot()).spec;
  if (const std::string problem = head_problem(spec, positions); !problem.empty()) {
    return reject(topic, positions.size() != spec.head_joints.size() ? "size" : "finite", problem);
  }
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const int j = spec.joint_index(spec.head_joints[i]);
    if (j < 0) continue;
    const JointSpec& js = spec.joints[static_cast<std::size_t>(j)];
    if (positions[i] < js.lower || positions[i] > js.upper) {
      const double limit = positions[i] < js.lower ? js.lower : js.upper;
      warn(topic + "#limit" + std::to_string(i),
           fmt::format("{} data[{}] ({}) = {:g} rad ({:.0f} deg) is beyond the joint's limits: clamped to {:g} rad ({:.0f} deg)", topic, i,
                       js.name, positions[i], positions[i] * kDeg, limit, limit * kDeg));
    }
  }
  if (const CommandOutcome r = host_.command_head(robot, positions); !r) {
    return reject(topic, "refused", "refused by the host: " + r.reason);
  }
  ++received_;
  return CommandOutcome::ok();
}

CommandOutcome CommandGate::flippers(RobotIndex robot, const std::string& topic, const std::vector<double>& positions) {
  const RobotSpec& spec = host_.world().robots.at(robot.slot()).spec;
  if (positions.size() != spec.flipper_joints.size()) {
    return reject(topic, "size",
                  fmt::format("{} positions, expected {} (rad, in the order {})", positions.size(), spec.flipper_joints.size(),
                              joined(spec.flipper_joints)));
  }
  msg::JointState command;
  command.name = spec.flipper_joints;
  command.position = positions;
  return joints(robot, topic, command);
}

CommandOutcome CommandGate::input(std::size_t index, const std::string& topic, const msg::Message& message) {
  if (const CommandOutcome r = host_.submit_input(index, message); !r) return reject(topic, "refused", "refused by the host: " + r.reason);
  ++received_;
  return CommandOutcome::ok();
}

CommandOutcome CommandGate::joints(RobotIndex robot, const std::string& topic, const msg::JointState& command) {
  if (const CommandOutcome r = host_.command_joints(robot, command); !r) return reject(topic, "joints", r.reason);
  // accepted: say which position targets were clamped to their joint's limits
  const RobotSpec& spec = host_.world().robots.at(robot.slot()).spec;
  for (std::size_t i = 0; i < command.name.size() && i < command.position.size(); ++i) {
    const int j = spec.joint_index(command.name[i]);
    if (j < 0) continue;
    const JointSpec& js = spec.joints[static_cast<std::size_t>(j)];
    if (js.control != JointSpec::Control::position || js.type == JointSpec::Type::continuous) continue;
    const double p = command.position[i];
    if (p < js.lower || p > js.upper) {
      warn(topic + "#limit:" + js.name, fmt::format("{} position of {} = {:g} is beyond the joint's limits [{:g}, {:g}]: clamped to {:g}",
                                                  topic, js.name, p, js.lower, js.upper, p < js.lower ? js.lower : js.upper));
    }
  }
  ++received_;
  return CommandOutcome::ok();
}

}  // namespace rescuesim
