#pragma once
/// Simulation: owns the World, the State, the physics engine, the ray scene and the sensors,
/// and steps them in phases:
///   PreStep   apply queued commands; drive and head controllers
///   Physics   one fixed step of Bullet
///   PostStep  odometry; every sensor due at this time samples a const State and publishes
/// Messages go to the Bus stamped with sim time. Commands may come from any thread; they
/// are queued and applied at the next step boundary, so a run's messages do not depend on
/// thread timing.

#include <chrono>
#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "physics/physics.h"
#include "raycast/ray_scene.h"
#include "sim/bus.h"
#include "world/state.h"
#include "world/world.h"

namespace rescuesim {

/// How topics and frames of several robots are told apart.
enum class Namespacing { automatic, always, never };

/// Settings of a simulation.
struct SimOptions {
  PhysicsOptions physics;
  std::uint64_t seed = 1;              ///< every noise stream derives from (seed, robot, sensor)
  double clock_rate = 0;               ///< Hz for /clock; 0 = every step
  double tf_rate = 50;                 ///< Hz for moving joints on /tf
  bool tf_from_ground_truth = false;   ///< odom -> base_link from ground truth instead of wheel odometry
  bool publish_map_to_odom = false;    ///< also map -> odom from ground truth
  Namespacing namespacing = Namespacing::automatic;  ///< automatic: prefixes only with two or more robots
  double victim_check_rate = 5;        ///< Hz: how often victims in view are looked for
};

/// A sensor of a robot, as the simulation schedules it.
struct SensorInstance {
  int robot = 0;
  int index = 0;                       ///< into the robot's spec.sensors
  int slot = 0;                        ///< into State::sensors
  int topic = -1;                      ///< Bus topic id of the main output
  int info_topic = -1;                 ///< cameras: camera_info
  int extra_topic = -1;                ///< depth: points; thermal: image_mono8
  std::string frame_id;                ///< header frame of its messages, namespaced; cameras: the optical frame
  SimTime period;
};

/// True when /joint_command may drive joint `j` of `spec`: a moving joint with a controller that
/// is neither a drive wheel (cmd_vel drives those), a head joint (/head/command) nor a mimic.
bool is_commandable(const RobotSpec& spec, std::size_t j);
/// Whether any joint of `spec` is commandable (the bridges subscribe joint_command only then).
bool has_commandable_joints(const RobotSpec& spec);

/// Renders camera sensors. The simulation hands it each camera sample as it falls due and,
/// after every step, asks it to deliver finished frames; an implementation may render on
/// another thread meanwhile (src/sensors/camera_service.h does), as long as what it delivers at
/// a given step never depends on thread timing.
class CameraService {
 public:
  virtual ~CameraService() = default;
  /// A camera is due at `state.time`: take what it needs from `state` and start its frame;
  /// draw any randomness from `slot.rng` now, on the simulation thread.
  virtual void sample(const World& world, const State& state, const SensorInstance& sensor, SensorSlot& slot) = 0;
  /// Publishes, in sample order, every frame due for delivery at or before `now` (waiting for
  /// it if it is not finished), and may record victims it saw in `state.victims`.
  virtual void deliver(const World& world, State& state, SimTime now, const std::function<void(int, msg::Message)>& publish) = 0;
  /// True when this service decides which victims are seen (from thermal images) for `robot`.
  virtual bool detects_victims(int robot) const = 0;
};

class Simulation {
 public:
  Simulation(World world, const SimOptions& options = {});
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  const World& world() const { return world_; }
  const State& state() const { return state_; }
  Bus& bus() { return bus_; }
  const SimOptions& options() const { return options_; }
  SimTime time() const { return state_.time; }
  double dt() const { return physics_->dt(); }
  const std::vector<SensorInstance>& sensors() const { return sensors_; }
  const RayScene& ray_scene() const { return *rays_; }

  /// One step of dt (the first call also publishes the state at t = 0: /tf_static, each robot's
  /// robot_description, first samples).
  void step();
  /// Steps until sim time reaches `t` (or trouble stops the run); returns false on trouble.
  bool step_until(SimTime t);
  /// True when numerical trouble stopped the simulation (see state().trouble).
  bool in_trouble() const { return state_.trouble.nan_poses + state_.trouble.escaped > 0; }

  /// cmd_vel for a robot: applied at the next step boundary. Non-finite values are rejected
  /// (returns false); the drive clamps the rest to its limits.
  bool command_velocity(int robot, const msg::Twist& twist);
  /// Head joint position targets (rad), one per head joint in RobotSpec::head_joints order.
  bool command_head(int robot, const std::vector<double>& positions);
  /// Targets for a robot's commandable joints by name (`/<robot>/joint_command`, a
  /// sensor_msgs/JointState): a position for position-controlled joints, a velocity for
  /// velocity-controlled ones; `position` and `velocity` may each be empty or hold one value per
  /// name. Applied at the next step boundary. Rejected (false, nothing applied) when a name is
  /// unknown, a drive wheel, fixed, passive or a mimic joint, or a value is missing or non-finite.
  /// Position targets beyond a joint's limits are clamped to them (like the head's); velocity
  /// targets are limited to max_velocity by the joint motor. When rejected and `why` is given,
  /// it says why ("position has 1 values for 2 names"), for the bridges' warnings.
  bool command_joints(int robot, const msg::JointState& command, std::string* why = nullptr);
  /// Drops the commands queued for the next step; returns how many. For owners that publish
  /// without stepping (rescuesim replay), so what bridges take in does not pile up.
  std::size_t discard_commands();
  /// Velocity commands accepted so far (every robot); with wait_for_velocity_commands, what a
  /// synchronous run (SessionOptions::sync_timeout) waits on.
  std::uint64_t velocity_commands() const;
  /// Waits until at least `count` velocity commands have been accepted in all, or `timeout`
  /// of wall time passes; returns whether they have.
  bool wait_for_velocity_commands(std::uint64_t count, std::chrono::duration<double> timeout);

  /// Robot index by name, or -1.
  int robot_index(const std::string& name) const;
  /// The absolute topic name of a robot's relative topic ("scan" -> "/scan" or "/robot2/scan").
  std::string topic_name(int robot, const std::string& relative) const;
  /// A robot's frame name ("base_link" -> "base_link" or "robot2/base_link").
  std::string frame_name(int robot, const std::string& frame) const;

  /// Cameras are sampled through this service when one is attached (none: cameras are skipped).
  void set_camera_service(CameraService* service) { cameras_ = service; }
  /// Publishes every camera frame still in flight (at the end of a run).
  void flush_cameras();

  /// A copy of the state, and a way back to it (see Physics::restore for the fine print).
  State snapshot() const { return state_; }
  void restore(const State& state);

 private:
  void setup_topics();
  void pre_step();
  void post_step();
  void sample(const SensorInstance& s);
  void publish_tf_static();
  void publish_descriptions();
  void publish_tf();
  void check_victims();
  bool namespaced() const;

  World world_;
  SimOptions options_;
  State state_;
  Bus bus_;
  std::unique_ptr<Physics> physics_;
  std::unique_ptr<RayScene> rays_;
  bool rays_current_ = false;
  std::vector<SensorInstance> sensors_;
  CameraService* cameras_ = nullptr;
  bool started_ = false;
  int clock_topic_ = -1, tf_topic_ = -1, tf_static_topic_ = -1;
  std::vector<int> description_topics_;  ///< per robot: its latched robot_description topic, -1 without a description
  SimTime next_clock_, next_tf_, next_victim_check_;

  /// A command waiting for the next step boundary.
  struct Command {
    enum class Kind { velocity, head, joints };
    int robot = 0;
    Kind kind = Kind::velocity;
    msg::Twist twist;                 ///< velocity
    std::vector<double> values;       ///< head: positions in head_joints order; joints: one target per `joints` entry
    std::vector<std::size_t> joints;  ///< joints: indices into the robot's spec.joints
  };
  mutable std::mutex commands_mutex_;
  std::vector<Command> commands_;
  std::uint64_t velocity_commands_ = 0;     ///< accepted so far (guarded by commands_mutex_)
  std::condition_variable command_arrived_;  ///< signalled when a velocity command is accepted
};

}  // namespace rescuesim
