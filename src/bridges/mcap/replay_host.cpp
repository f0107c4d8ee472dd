#include "bridges/mcap/replay_host.h"

namespace rescuesim {

ReplayHost::ReplayHost(const World& world, std::uint64_t seed) : world_(world), seed_(seed), state_(initial_state(world)) {}

// names as a simulation of this world with automatic namespacing gives them (prefixed only
// when there are two robots or more), so bridges take in and send the recorded names
std::string ReplayHost::topic_name(RobotIndex robot, const std::string& relative) const {
  if (!relative.empty() && relative[0] == '/') return relative;
  return world_.robots.size() > 1 ? "/" + world_.robot(robot).name + "/" + relative : "/" + relative;
}

std::string ReplayHost::frame_name(RobotIndex robot, const std::string& frame) const {
  if (frame == "map" || frame.empty()) return frame;
  return world_.robots.size() > 1 ? world_.robot(robot).name + "/" + frame : frame;
}

CommandOutcome ReplayHost::command_velocity(RobotIndex, const msg::Twist&) {
  ++discarded_;
  return CommandOutcome::ok();
}

CommandOutcome ReplayHost::command_head(RobotIndex, const std::vector<double>&) {
  ++discarded_;
  return CommandOutcome::ok();
}

CommandOutcome ReplayHost::command_joints(RobotIndex, const msg::JointState&) {
  ++discarded_;
  return CommandOutcome::ok();
}

}  // namespace rescuesim
