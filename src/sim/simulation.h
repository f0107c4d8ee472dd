#pragma once
/// Simulation: owns the World, the State, the physics engine, the ray scene and the sensors,
/// and steps them in phases:
///   PreStep   apply queued commands; drive and head controllers
///   Physics   one fixed step of Bullet
///   PostStep  odometry; every sensor due at this time samples a const State and publishes
/// Messages go to the Bus stamped with sim time. Commands may come from any thread; they
/// are queued and applied at the next step boundary, so a run's messages do not depend on
/// thread timing.

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "physics/physics.h"
#include "raycast/ray_scene.h"
#include "sensors/camera_service.h"    // CameraService (its renderer: sensors/camera/render_camera_service.h)
#include "sensors/sensor_instance.h"
#include "sensors/victim_detector.h"
#include "bus/bridge_host.h"
#include "bus/bus.h"
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

/// The simulation is the BridgeHost of a run: bridges attach to it through that interface.
class Simulation : public BridgeHost {
 public:
  Simulation(World world, const SimOptions& options = {});
  ~Simulation() override;
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  /// The world now. Robots and loose bodies added or removed while running (add_robot,
  /// remove_robot, ...) make a new version; every version lives as long as the Simulation, so a
  /// reference taken on any thread stays valid (and unchanged), and world() may be called from
  /// any thread (bridges' command checks do).
  const World& world() const override { return *world_.load(std::memory_order_acquire); }
  const State& state() const override { return state_; }
  Bus& bus() override { return bus_; }
  const SimOptions& options() const { return options_; }
  SimTime time() const override { return state_.time; }
  std::uint64_t seed() const override { return options_.seed; }
  HostFrames frames() const override { return {options_.publish_map_to_odom, options_.tf_from_ground_truth}; }
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

  /// Commands, from any thread (the BridgeHost interface, and the owners of the run): each is
  /// queued and applied at the next step boundary, or refused with its reason (the outcome is
  /// false and says why; nothing is applied).
  /// cmd_vel for a robot. Non-finite values are refused; the drive clamps the rest to its limits.
  CommandOutcome command_velocity(RobotIndex robot, const msg::Twist& twist) override;
  /// Head joint position targets (rad), one per head joint in RobotSpec::head_joints order.
  CommandOutcome command_head(RobotIndex robot, const std::vector<double>& positions) override;
  /// Targets for a robot's commandable joints by name (`/<robot>/joint_command`, a
  /// sensor_msgs/JointState): a position for position-controlled joints, a velocity for
  /// velocity-controlled ones; `position` and `velocity` may each be empty or hold one value per
  /// name. Refused when a name is unknown, a drive wheel, fixed, passive or a mimic joint, or a
  /// value is missing or non-finite ("position has 1 values for 2 names"). Position targets
  /// beyond a joint's limits are clamped to them (like the head's); velocity targets are
  /// limited to max_velocity by the joint motor.
  CommandOutcome command_joints(RobotIndex robot, const msg::JointState& command) override;
  /// Drops the commands queued for the next step; returns how many. For owners that publish
  /// without stepping (rescuesim replay), so what bridges take in does not pile up.
  std::size_t discard_commands();
  /// Velocity commands accepted so far (every robot); with wait_for_velocity_commands, what a
  /// synchronous run (SessionOptions::sync_timeout) waits on.
  std::uint64_t velocity_commands() const;
  /// Adds a topic bridges take in for an owner above the simulation (a Mission: reports,
  /// datagrams, relay drops) and returns its index in inputs(). Every message submitted for it
  /// (submit_input, from any thread) is handed to `handler` on the stepping thread at the next
  /// step boundary, before the commands, in arrival order. Add inputs before bridges start.
  /// At most kMaxQueuedInputs messages wait between two steps; more are refused ("full").
  std::size_t add_input(HostInput input, std::function<void(const msg::Message&)> handler);
  std::vector<HostInput> inputs() const override;
  CommandOutcome submit_input(std::size_t index, const msg::Message& message) override;
  static constexpr std::size_t kMaxQueuedInputs = 4096;
  /// Waits until at least `count` velocity commands have been accepted in all, or `timeout`
  /// of wall time passes; returns whether they have.
  bool wait_for_velocity_commands(std::uint64_t count, std::chrono::duration<double> timeout);

  /// Robot index by name; invalid when there is none.
  RobotIndex robot_index(const std::string& name) const;
  /// The absolute topic name of a robot's relative topic ("scan" -> "/scan" or "/robot2/scan").
  std::string topic_name(RobotIndex robot, const std::string& relative) const override;
  /// A robot's frame name ("base_link" -> "base_link" or "robot2/base_link").
  std::string frame_name(RobotIndex robot, const std::string& frame) const override;

  /// Cameras are sampled through this service when one is attached (none: cameras are skipped).
  /// Not owned: the caller keeps the service alive while it is attached and detaches it
  /// (set_camera_service(nullptr)) before destroying it, or destroys the Simulation first;
  /// the service must not be used by two simulations. Session owns its RenderCameraService
  /// and detaches it in its destructor.
  void set_camera_service(CameraService* service) { cameras_ = service; }
  /// Called when the world changes while running (add_robot, remove_robot, ...), after the
  /// camera frames in flight were published and the new world made current, before the new
  /// robots' sensors are set up: the owner of the camera service builds it afresh for world()
  /// here (a camera service draws the world it was made with).
  void set_world_changed(std::function<void()> callback) { world_changed_ = std::move(callback); }
  /// The control surface bridges offer (bus/sim_control.h); not owned. Session sets its
  /// RunControl here; without one, control() is null and bridges offer no services.
  void set_control(control::SimControl* control) { control_ = control; }
  control::SimControl* control() override { return control_; }
  /// How victims are found (victim_check_rate); owned. Default, and with nullptr: line of
  /// sight for every robot. Set once at set-up, before the first step (Session does).
  void set_victim_detector(std::unique_ptr<VictimDetector> detector);
  const VictimDetector& victim_detector() const { return *victim_detector_; }
  /// Publishes every camera frame still in flight (at the end of a run).
  void flush_cameras();

  // ---- robots and loose bodies added and removed while running (SpawnEntity, DeleteEntity) ----
  // On the stepping thread, between steps. Each change publishes the camera frames in flight,
  // rebuilds the physics engine and the ray scene from the new world and restores the State
  // into them (Physics::restore: the canonical form a snapshot also takes), lets the camera
  // service's owner build it afresh (set_world_changed), advertises the new robot's topics (a
  // spawned robot's are under its namespace: RobotInstance::ns), retires a removed robot's, and
  // tells the Bus's layout watchers (the bridges). A spawned robot has no /lights input.

  /// Adds a robot, placed (world/world.h: place_robot) and with `spawned` and `ns` set, its
  /// name unused; it starts at rest at its X_W_start, its sensors due at once. Returns its index.
  RobotIndex add_robot(RobotInstance robot);
  /// Adds a loose rigid body (spawned set) at its X_WO, at rest; returns its index in World::dynamics.
  std::size_t add_body(DynamicObject body);
  /// Removes a spawned robot: the robots after it move down one index (commands queued for them
  /// follow them; bridges remap their command inputs when the layout watchers are called).
  void remove_robot(RobotIndex robot);
  /// Removes a spawned loose body.
  void remove_body(std::size_t body);
  /// Removes every spawned robot and body (a reset of spawned entities).
  void remove_spawned();
  /// How many robots and loose bodies the simulation was made with (they come first and stay).
  std::size_t base_robots() const { return base_robots_; }
  std::size_t base_bodies() const { return base_dynamics_; }

  /// A copy of the whole changing state — bodies, joints, controller and sensor memory, RNG
  /// streams, the /clock, /tf and victim-check schedule — to restore() later. Exact: run on
  /// from a snapshot, restore it, run again with the same commands, and the messages and
  /// state_hash are bitwise the same. The price is that a snapshot is a synchronisation point
  /// for the physics engine: it drops Bullet's contact caches (warm start) and rebuilds its
  /// broadphase in a canonical order (Physics::restore), so a run that takes a snapshot is
  /// bitwise equal to its own replays but not to a run that never took one (the golden hash
  /// test takes none). The cost is a State copy and one Physics::restore: about 0.3 ms for the
  /// default world (`rescuesim bench --reset-only`). Built-in controllers and camera frames in
  /// flight live outside the Simulation: Session::snapshot covers them.
  State snapshot();
  /// Puts the simulation back to a state from snapshot() of this simulation (same World and
  /// options); publishing resumes on the state's own schedule at once. A state taken before
  /// anything was spawned removes what was spawned since (remove_spawned) first; a state taken
  /// with spawned entities restores only while the same ones are there. Commands queued and not
  /// yet applied stay queued; the Bus's message counts are not rewound.
  void restore(const State& state);

 private:
  void setup_topics();
  /// description_topics_ and sensors_ for the robots of world() (advertising what is new).
  void setup_robot_topics();
  SensorSlot new_slot(const SensorInstance& s, SimTime first_due) const;
  /// Old robot index -> new (invalid: gone), for a change of the world's robots.
  using RobotMap = IndexedVector<RobotTag, RobotIndex>;
  /// Makes `next` the world and `next_state` the state (which fits it): new physics and ray
  /// scene, robot topics, retired topics of robots gone, queued commands moved by `robot_map`
  /// (old index -> new, invalid: gone); then the layout watchers.
  void rebuild(std::unique_ptr<const World> next, State next_state, const RobotMap& robot_map);
  /// Makes world version `next` current (already in worlds_), under the command lock, moving
  /// queued commands by `robot_map`.
  void switch_world(const World* next, const RobotMap& robot_map);
  /// The rest of rebuild, for a version already in worlds_.
  void adopt(const World* next, State next_state, const RobotMap& robot_map);
  void pre_step();
  void post_step();
  void sample(const SensorInstance& s);
  static bool ray_sensor(SensorSpec::Type type);
  /// The ray scene, brought up to state_ first if it is not (not while another thread casts).
  const RayScene& current_rays();
  /// A lidar's or sonar's message now; safe to call for different sensors at once.
  msg::Message sample_rays(const SensorInstance& s, const RayScene& scene);
  void publish_tf_static();
  void publish_descriptions();
  void publish_tf();
  void check_victims();

  std::vector<std::unique_ptr<const World>> worlds_;  ///< every version (worlds_[0]: as made); kept to the end
  std::atomic<const World*> world_{nullptr};          ///< the current version
  std::size_t base_robots_ = 0, base_dynamics_ = 0;
  bool base_namespaced_ = false;                      ///< the scenario's robots' topics are under their names
  SimOptions options_;
  State state_;
  Bus bus_;
  std::unique_ptr<Physics> physics_;
  std::unique_ptr<RayScene> rays_;
  bool rays_current_ = false;          ///< the ray scene shows state_ (a cache: restore clears it)
  std::vector<SensorInstance> sensors_;
  control::SimControl* control_ = nullptr;  ///< not owned (Session's RunControl)
  std::function<void()> world_changed_;
  CameraService* cameras_ = nullptr;  ///< not owned (set_camera_service says how long it must live)
  std::unique_ptr<VictimDetector> victim_detector_ = std::make_unique<LineOfSightDetector>();
  TopicId clock_topic_ = kNoTopic, tf_topic_ = kNoTopic, tf_static_topic_ = kNoTopic;
  std::vector<TopicId> description_topics_;  ///< per robot: its latched robot_description topic, kNoTopic without a description

  /// A command waiting for the next step boundary.
  struct Command {
    enum class Kind { velocity, head, joints };
    RobotIndex robot{0};
    Kind kind = Kind::velocity;
    msg::Twist twist;                 ///< velocity
    std::vector<double> values;       ///< head: positions in head_joints order; joints: one target per `joints` entry
    std::vector<std::size_t> joints;  ///< joints: indices into the robot's spec.joints
  };
  mutable std::mutex commands_mutex_;
  std::vector<Command> commands_;
  struct Input {
    HostInput topic;
    std::function<void(const msg::Message&)> handler;
  };
  std::vector<Input> inputs_;                                      ///< fixed before bridges start
  std::vector<std::pair<std::size_t, msg::Message>> input_queue_;  ///< guarded by commands_mutex_
  std::uint64_t velocity_commands_ = 0;     ///< accepted so far (guarded by commands_mutex_)
  std::condition_variable command_arrived_;  ///< signalled when a velocity command is accepted
};

}  // namespace rescuesim
