#pragma once
/// BridgeHost: all that a bridge (src/bridges/*) may use of what it is attached to. A running
/// Simulation is one host; a replay (bridges/mcap/replay_host.h) is another, with a Bus and a
/// clock but no physics, so a transport written against this interface works for both and
/// replay never builds Bullet or Embree.
///
/// Threads: bus(), world(), state(), time() and the naming calls are for the thread that
/// publishes (a bridge's start() and its Bus callbacks); the submit_* calls may come from any
/// thread (a bridge's receive thread): the host queues or discards them.

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/sim_time.h"
#include "msgs/messages.h"
#include "bus/bus.h"
#include "bus/sim_control.h"
#include "world/state.h"
#include "world/world.h"

namespace rescuesim {

/// True when /joint_command may drive joint `j` of `spec`: a moving joint with a controller that
/// is neither a drive wheel (cmd_vel drives those), a head joint (/head/command) nor a mimic.
bool is_commandable(const RobotSpec& spec, std::size_t j);
/// Whether any joint of `spec` is commandable (the bridges subscribe joint_command only then).
bool has_commandable_joints(const RobotSpec& spec);

/// The outcome of a command handed to a host: taken, or refused with the reason.
struct CommandOutcome {
  bool accepted = false;
  std::string reason;  ///< why it was refused, for the bridge's warning ("names 2 joints but has 1 positions")

  static CommandOutcome ok() { return {true, {}}; }
  static CommandOutcome refused(std::string why) { return {false, std::move(why)}; }
  explicit operator bool() const { return accepted; }
};

/// How the host publishes its frames, for bridges that draw the world themselves (Foxglove's
/// scene): see SimOptions.
struct HostFrames {
  bool publish_map_to_odom = false;   ///< map -> odom is on /tf
  bool tf_from_ground_truth = false;  ///< odom -> base_link is ground truth (odom coincides with the world)
};

/// A topic a host takes messages on beyond the built-in commands (a mission's victim reports,
/// datagrams and relay drops): bridges subscribe it on their transport with `type` and hand
/// every message that decodes to submit_input(), with its index in inputs().
struct HostInput {
  std::string topic;  ///< absolute name ("/robot2/rescue/report")
  std::string type;   ///< ROS 1 type name ("geometry_msgs/PoseStamped"); msgs/serialize.h has its serialisers
  RobotIndex robot;   ///< the robot it belongs to; invalid for none
};

class BridgeHost {
 public:
  virtual ~BridgeHost() = default;

  /// Where messages are published and topics advertised.
  virtual Bus& bus() = 0;
  /// The compiled world: robots (names, specs: head joints, links, drive limits, description).
  virtual const World& world() const = 0;
  /// The current state (rubble poses, victims found); for a replay, the state at the start
  /// with the clock at replay time.
  virtual const State& state() const = 0;
  /// Sim time now (a replay: the log time of the message being published).
  virtual SimTime time() const = 0;
  /// The run's seed (reported to clients).
  virtual std::uint64_t seed() const = 0;
  virtual HostFrames frames() const = 0;

  /// The absolute topic name of a robot's relative topic ("scan" -> "/scan" or "/robot2/scan").
  virtual std::string topic_name(RobotIndex robot, const std::string& relative) const = 0;
  /// A robot's frame name ("base_link" -> "base_link" or "robot2/base_link").
  virtual std::string frame_name(RobotIndex robot, const std::string& frame) const = 0;

  /// cmd_vel for robot `robot` (an index into world().robots), applied at the next step.
  virtual CommandOutcome command_velocity(RobotIndex robot, const msg::Twist& twist) = 0;
  /// Head joint position targets (rad), in RobotSpec::head_joints order.
  virtual CommandOutcome command_head(RobotIndex robot, const std::vector<double>& positions) = 0;
  /// Targets for commandable joints by name (see Simulation::command_joints).
  virtual CommandOutcome command_joints(RobotIndex robot, const msg::JointState& command) = 0;

  /// Topics taken beyond the commands above; fixed before bridges start. None by default.
  virtual std::vector<HostInput> inputs() const { return {}; }
  /// A message for inputs()[index] (of its type), handed over at the next step boundary.
  virtual CommandOutcome submit_input(std::size_t index, const msg::Message& message) {
    (void)index;
    (void)message;
    return CommandOutcome::refused("this host takes no inputs");
  }

  /// The run's control surface (reset, pause, step, entities, parameters: bus/sim_control.h),
  /// or null when the host cannot be controlled (a replay, a bare Simulation without a Session).
  virtual control::SimControl* control() { return nullptr; }
};

}  // namespace rescuesim
