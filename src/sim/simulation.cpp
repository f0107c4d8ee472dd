#include "sim/simulation.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/parallel.h"
#include "robots/drive_controller.h"
#include "sensors/contact.h"
#include "sensors/ground_truth.h"
#include "sensors/imu.h"
#include "sensors/joint_state.h"
#include "sensors/lidar.h"
#include "sensors/odometry.h"
#include "sensors/sonar.h"

namespace rescuesim {

namespace {

SimTime period_of(double rate) { return SimTime::from_seconds(1.0 / rate); }

/// A stamped transform, built field by field.
msg::TransformStamped transform(SimTime stamp, const std::string& parent, const std::string& child, const Pose3& X) {
  msg::TransformStamped t;
  t.header.stamp = stamp;
  t.header.frame_id = parent;
  t.child_frame_id = child;
  t.transform = X;
  return t;
}

/// The optical frame beside a camera's body frame, named as ROS drivers do.
std::string optical_frame(const std::string& body_frame) { return body_frame + "_optical_frame"; }

bool contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

bool is_wheel(const RobotSpec& spec, const std::string& joint) {
  return contains(spec.drive.left_wheels, joint) || contains(spec.drive.right_wheels, joint);
}

/// What a joint that /joint_command may not drive is, for the refusal.
const char* kind_of_uncommandable(const RobotSpec& spec, const JointSpec& js) {
  if (js.type == JointSpec::Type::fixed) return "a fixed joint";
  if (is_wheel(spec, js.name)) return "a drive wheel (use cmd_vel)";
  if (contains(spec.head_joints, js.name)) return "a head joint (use head/command)";
  if (!js.mimic.empty()) return "a mimic joint (it follows its leader)";
  return "a passive joint (no controller)";
}

}  // namespace

bool is_commandable(const RobotSpec& spec, std::size_t j) {
  if (j >= spec.joints.size()) return false;
  const JointSpec& js = spec.joints[j];
  return js.type != JointSpec::Type::fixed && js.control != JointSpec::Control::none && js.mimic.empty() && !is_wheel(spec, js.name) &&
         !contains(spec.head_joints, js.name);
}

bool has_commandable_joints(const RobotSpec& spec) {
  for (std::size_t j = 0; j < spec.joints.size(); ++j) {
    if (is_commandable(spec, j)) return true;
  }
  return false;
}

Simulation::Simulation(World initial, const SimOptions& options) : options_(options) {
  worlds_.push_back(std::make_unique<const World>(std::move(initial)));
  world_.store(worlds_.back().get(), std::memory_order_release);
  base_robots_ = world().robots.size();
  base_dynamics_ = world().dynamics.size();
  base_namespaced_ = options_.namespacing == Namespacing::always || (options_.namespacing == Namespacing::automatic && base_robots_ > 1);
  physics_ = std::make_unique<Physics>(world(), options_.physics);
  rays_ = std::make_unique<RayScene>(world());
  physics_->init_state(state_);
  state_.victims.assign(world().victims.size(), VictimState{});
  for (auto& r : state_.robots) r.odom = Pose2{};
  setup_topics();
}

Simulation::~Simulation() = default;

std::string Simulation::topic_name(RobotIndex robot, const std::string& relative) const {
  if (!relative.empty() && relative[0] == '/') return relative;
  const RobotInstance& r = world().robot(robot);
  // a spawned robot is always under its namespace; the scenario's robots are namespaced as the
  // options say for the robots the run started with, so their names never change
  if (r.spawned) return "/" + r.ns + "/" + relative;
  return base_namespaced_ ? "/" + r.name + "/" + relative : "/" + relative;
}

std::string Simulation::frame_name(RobotIndex robot, const std::string& frame) const {
  if (frame == "map" || frame.empty()) return frame;
  const RobotInstance& r = world().robot(robot);
  if (r.spawned) return r.ns + "/" + frame;
  return base_namespaced_ ? r.name + "/" + frame : frame;
}

RobotIndex Simulation::robot_index(const std::string& name) const {
  for (RobotIndex r : world().robot_indices()) {
    if (world().robot(r).name == name) return r;
  }
  return {};
}

void Simulation::setup_topics() {
  clock_topic_ = bus_.advertise("/clock", "rosgraph_msgs/Clock", options_.clock_rate > 0 ? options_.clock_rate : 1.0 / dt());
  tf_topic_ = bus_.advertise("/tf", "tf2_msgs/TFMessage", options_.tf_rate);
  tf_static_topic_ = bus_.advertise("/tf_static", "tf2_msgs/TFMessage", 0, true);
  // a robot with lamps switches them all on and off with /lights (std_msgs/Bool)
  for (std::size_t r = 0; r < world().robots.size(); ++r) {
    if (world().robots[r].spec.lights.empty()) continue;
    add_input({topic_name(RobotIndex::at(r), "lights"), "std_msgs/Bool", RobotIndex::at(r)},
              [this, r](const msg::Message& m) { state_.robots[r].lights_on = std::get<msg::Bool>(m).data; });
  }
  setup_robot_topics();
  // one random stream and one schedule per sensor, in robot and spec order
  for (const SensorInstance& s : sensors_) state_.sensors.push_back(new_slot(s, SimTime{0}));
}

SensorSlot Simulation::new_slot(const SensorInstance& s, SimTime first_due) const {
  SensorSlot slot;
  slot.rng = Rng(options_.seed, "sensor/" + world().robot(s.robot).name + "/" + s.spec.name);
  slot.next_due = first_due;
  return slot;
}

void Simulation::setup_robot_topics() {
  // a robot loaded from a description (URDF) offers it, latched, as robot_state_publisher does
  description_topics_.assign(world().robots.size(), kNoTopic);
  for (std::size_t r = 0; r < world().robots.size(); ++r) {
    if (world().robots[r].spec.description.empty()) continue;
    const RobotIndex ri = RobotIndex::at(r);
    description_topics_[r] = bus_.advertise(topic_name(ri, "robot_description"), "std_msgs/String", 0, true, ri);
  }
  // the sensors, in robot and spec order; slot k of the State is sensor k's
  sensors_.clear();
  for (std::size_t r = 0; r < world().robots.size(); ++r) {
    const RobotInstance& robot = world().robots[r];
    for (std::size_t i = 0; i < robot.spec.sensors.size(); ++i) {
      const SensorSpec& spec = robot.spec.sensors[i];
      if (!spec.enabled) continue;
      SensorInstance s;
      s.robot = RobotIndex::at(r);
      s.index = static_cast<int>(i);
      s.slot = static_cast<int>(sensors_.size());
      s.period = period_of(spec.rate);
      // images are in an optical frame (z forward, x right, y down) beside the camera's body frame (REP-103)
      s.frame_id = frame_name(s.robot, spec.is_camera() ? optical_frame(spec.frame_id) : spec.frame_id);
      s.spec = spec;
      s.spec.frame_id = s.frame_id;
      // the main topic, then what the kind publishes beside it, in the folder of the main topic
      const std::string topic = topic_name(s.robot, spec.topic);
      s.topic = bus_.advertise(topic, spec.ros_type(), spec.rate, false, s.robot);
      const std::string folder = topic.substr(0, topic.rfind('/') + 1);
      if (spec.is_camera()) {
        s.info_topic = bus_.advertise(folder + kCameraInfoTopic.name, kCameraInfoTopic.ros_type, spec.rate, false, s.robot);
      }
      if (const SensorExtraTopic* extra = spec.extra_topic()) {
        s.extra_topic = bus_.advertise(folder + extra->name, extra->ros_type, spec.rate, false, s.robot);
      }
      sensors_.push_back(s);
    }
  }
}

CommandOutcome Simulation::command_velocity(RobotIndex robot, const msg::Twist& t) {
  if (!world().has_robot(robot)) return CommandOutcome::refused("no robot " + std::to_string(robot.value()));
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(t.linear[i]) || !std::isfinite(t.angular[i])) return CommandOutcome::refused("a value is not finite");
  }
  {
    std::lock_guard lock(commands_mutex_);
    Command c;
    c.robot = robot;
    c.kind = Command::Kind::velocity;
    c.twist = t;
    commands_.push_back(std::move(c));
    ++velocity_commands_;
  }
  command_arrived_.notify_all();
  return CommandOutcome::ok();
}

std::uint64_t Simulation::velocity_commands() const {
  std::lock_guard lock(commands_mutex_);
  return velocity_commands_;
}

bool Simulation::wait_for_velocity_commands(std::uint64_t count, std::chrono::duration<double> timeout) {
  std::unique_lock lock(commands_mutex_);
  return command_arrived_.wait_for(lock, timeout, [&] { return velocity_commands_ >= count; });
}

CommandOutcome Simulation::command_head(RobotIndex robot, const std::vector<double>& positions) {
  if (!world().has_robot(robot)) return CommandOutcome::refused("no robot " + std::to_string(robot.value()));
  const std::size_t joints = world().robot(robot).spec.head_joints.size();
  if (positions.size() != joints) {
    return CommandOutcome::refused(std::to_string(positions.size()) + " positions for " + std::to_string(joints) + " head joints");
  }
  for (double p : positions) {
    if (!std::isfinite(p)) return CommandOutcome::refused("a position is not finite");
  }
  Command c;
  c.robot = robot;
  c.kind = Command::Kind::head;
  c.values = positions;
  std::lock_guard lock(commands_mutex_);
  commands_.push_back(std::move(c));
  return CommandOutcome::ok();
}

CommandOutcome Simulation::command_joints(RobotIndex robot, const msg::JointState& command) {
  const auto refuse = [](std::string text) { return CommandOutcome::refused(std::move(text)); };
  if (!world().has_robot(robot)) return refuse("no robot " + std::to_string(robot.value()));
  const RobotSpec& spec = world().robot(robot).spec;
  const std::size_t n = command.name.size();
  if (n == 0) return refuse("no joint names");
  for (const auto& [field, values] : {std::pair<const char*, const std::vector<double>*>{"position", &command.position},
                                      {"velocity", &command.velocity}}) {
    if (!values->empty() && values->size() != n) {
      return refuse(std::string(field) + " has " + std::to_string(values->size()) + " values for " + std::to_string(n) +
                    " names (give one per name, or none)");
    }
  }
  // every name must be a commandable joint, named once, with a finite value of the kind its controller takes
  Command c;
  c.robot = robot;
  c.kind = Command::Kind::joints;
  for (std::size_t i = 0; i < n; ++i) {
    const std::string& name = command.name[i];
    const int j = spec.joint_index(name);
    if (j < 0) return refuse("'" + name + "' is not a joint of " + spec.model);
    const auto ju = static_cast<std::size_t>(j);
    const JointSpec& js = spec.joints[ju];
    if (!is_commandable(spec, ju)) return refuse("'" + name + "' is " + kind_of_uncommandable(spec, js) + ": not commandable");
    if (std::find(c.joints.begin(), c.joints.end(), ju) != c.joints.end()) return refuse("'" + name + "' is named twice");
    const bool position = js.control == JointSpec::Control::position;
    const std::vector<double>& values = position ? command.position : command.velocity;
    const std::string field = position ? "position" : "velocity";
    if (values.empty()) return refuse("'" + name + "' is " + field + "-controlled but the command has no " + field);
    double v = values[i];
    if (!std::isfinite(v)) return refuse(field + "[" + std::to_string(i) + "] ('" + name + "') is not finite");
    // position targets stay within the joint's limits (a continuous joint has none)
    if (position && js.type != JointSpec::Type::continuous) v = std::clamp(v, js.lower, js.upper);
    c.joints.push_back(ju);
    c.values.push_back(v);
  }
  std::lock_guard lock(commands_mutex_);
  commands_.push_back(std::move(c));
  return CommandOutcome::ok();
}

std::size_t Simulation::discard_commands() {
  std::lock_guard lock(commands_mutex_);
  const std::size_t n = commands_.size() + input_queue_.size();
  commands_.clear();
  input_queue_.clear();
  return n;
}

std::size_t Simulation::add_input(HostInput input, std::function<void(const msg::Message&)> handler) {
  RS_DEMAND(handler, "Simulation::add_input needs a handler");
  inputs_.push_back({std::move(input), std::move(handler)});
  return inputs_.size() - 1;
}

std::vector<HostInput> Simulation::inputs() const {
  std::vector<HostInput> out;
  for (const auto& in : inputs_) out.push_back(in.topic);
  return out;
}

CommandOutcome Simulation::submit_input(std::size_t index, const msg::Message& message) {
  if (index >= inputs_.size()) return CommandOutcome::refused("no input " + std::to_string(index));
  if (inputs_[index].topic.type != msg::type_name(message)) {
    return CommandOutcome::refused("a " + std::string(msg::type_name(message)) + " where " + inputs_[index].topic.type + " is expected");
  }
  std::lock_guard lock(commands_mutex_);
  if (input_queue_.size() >= kMaxQueuedInputs) {
    return CommandOutcome::refused("full: " + std::to_string(kMaxQueuedInputs) + " messages already wait for the next step");
  }
  input_queue_.emplace_back(index, message);
  return CommandOutcome::ok();
}

void Simulation::pre_step() {
  // inputs, then commands queued since the last step, each in arrival order
  std::vector<Command> pending;
  std::vector<std::pair<std::size_t, msg::Message>> inputs;
  {
    std::lock_guard lock(commands_mutex_);
    pending.swap(commands_);
    inputs.swap(input_queue_);
  }
  for (const auto& [index, m] : inputs) inputs_[index].handler(m);
  for (const auto& c : pending) {
    if (!world().has_robot(c.robot)) continue;  // its robot was removed meanwhile
    RobotState& rs = state_.robot(c.robot);
    switch (c.kind) {
      case Command::Kind::velocity:
        rs.cmd_linear = c.twist.linear;
        rs.cmd_angular = c.twist.angular;
        rs.cmd_time = state_.time;
        break;
      case Command::Kind::head: rs.head_target = c.values; break;
      case Command::Kind::joints:
        // joints the command does not name keep their targets
        rs.joint_target.resize(world().robot(c.robot).spec.joints.size(), 0.0);
        for (std::size_t i = 0; i < c.joints.size(); ++i) rs.joint_target[c.joints[i]] = c.values[i];
        break;
    }
  }
  for (std::size_t r = 0; r < world().robots.size(); ++r) {
    update_drive(world().robots[r].spec, state_.robots[r], state_.time, dt());
    update_head(world().robots[r].spec, state_.robots[r]);
  }
}

void Simulation::step() {
  if (in_trouble()) return;
  if (!state_.schedule.started) {
    state_.schedule.started = true;
    publish_tf_static();
    publish_descriptions();
    post_step();
  }
  pre_step();
  const std::vector<Vec3> before = [&] {
    std::vector<Vec3> p;
    for (const auto& r : state_.robots) p.push_back(r.base.X_WB.p);
    return p;
  }();
  physics_->step(state_);
  state_.time += SimTime::from_seconds(dt());
  ++state_.step;
  rays_current_ = false;
  for (std::size_t r = 0; r < state_.robots.size(); ++r)
    state_.robots[r].distance += (state_.robots[r].base.X_WB.p - before[r]).head<2>().norm();
  // wheel odometry integrates every step, whatever rate it publishes at
  for (const auto& s : sensors_) {
    const SensorSpec& spec = world().robot(s.robot).spec.sensors[static_cast<std::size_t>(s.index)];
    if (spec.type == SensorSpec::Type::odometry)
      integrate_odometry(world(), state_, s.robot, spec, dt(), state_.sensors[static_cast<std::size_t>(s.slot)]);
  }
  if (in_trouble()) return;
  post_step();
}

bool Simulation::step_until(SimTime t) {
  while (state_.time < t && !in_trouble()) step();
  return !in_trouble();
}

void Simulation::post_step() {
  const SimTime now = state_.time;
  Schedule& due = state_.schedule;
  if (now >= due.next_clock) {
    bus_.publish(clock_topic_, msg::Clock{now});
    due.next_clock = options_.clock_rate > 0 ? due.next_clock + period_of(options_.clock_rate) : now + SimTime{1};
  }
  // the ray sensors due now (lidars and sonars: most of the sampling work) sample at the same
  // time on the worker threads, each from the const state with its own RNG stream into its own
  // message; then every due sensor publishes in the fixed sensor order, so subscribers see the
  // same messages in the same order whatever the thread count
  std::vector<std::size_t> due_rays;
  for (std::size_t k = 0; k < sensors_.size(); ++k) {
    if (now >= state_.sensors[static_cast<std::size_t>(sensors_[k].slot)].next_due && ray_sensor(sensors_[k].spec.type))
      due_rays.push_back(k);
  }
  std::vector<msg::Message> ray_messages(due_rays.size());
  if (!due_rays.empty()) {
    const RayScene& scene = current_rays();
    parallel_for(due_rays.size(), [&](std::size_t i) { ray_messages[i] = sample_rays(sensors_[due_rays[i]], scene); });
  }
  std::size_t next_ray = 0;
  for (std::size_t k = 0; k < sensors_.size(); ++k) {
    const SensorInstance& s = sensors_[k];
    SensorSlot& slot = state_.sensors[static_cast<std::size_t>(s.slot)];
    if (now < slot.next_due) continue;
    if (next_ray < due_rays.size() && due_rays[next_ray] == k) {
      bus_.publish(s.topic, std::move(ray_messages[next_ray++]));
    } else {
      sample(s);
    }
    ++slot.count;
    // the next due time keeps the nominal grid, even if a step overshot this one
    while (slot.next_due <= now) slot.next_due += s.period;
  }
  if (now >= due.next_tf) {
    publish_tf();
    while (due.next_tf <= now) due.next_tf += period_of(options_.tf_rate);
  }
  if (cameras_) cameras_->deliver(world(), state_, now, [this](TopicId topic, msg::Message m) { bus_.publish(topic, std::move(m)); });
  if (now >= due.next_victim_check && !world().victims.empty()) {
    check_victims();
    while (due.next_victim_check <= now) due.next_victim_check += period_of(options_.victim_check_rate);
  }
}

bool Simulation::ray_sensor(SensorSpec::Type type) { return type == SensorSpec::Type::lidar || type == SensorSpec::Type::sonar; }

const RayScene& Simulation::current_rays() {
  if (!rays_current_) {
    rays_->update(state_);
    rays_current_ = true;
  }
  return *rays_;
}

msg::Message Simulation::sample_rays(const SensorInstance& s, const RayScene& scene) {
  // samplers take the spec framed at set-up (namespaced frame_id) and this sensor's slot, whose
  // RNG stream only this call draws from
  const SensorSpec& spec = s.spec;
  Rng& rng = state_.sensors[static_cast<std::size_t>(s.slot)].rng;
  const SimTime now = state_.time;
  if (spec.type == SensorSpec::Type::sonar) return sample_sonar(world(), state_, scene, s.robot, spec, now, rng);
  RS_DEMAND(spec.type == SensorSpec::Type::lidar, "Simulation::sample_rays: not a ray sensor");
  if (spec.lidar.layers > 1) return sample_lidar_cloud(world(), state_, scene, s.robot, spec, now, rng);
  return sample_lidar(world(), state_, scene, s.robot, spec, now, rng);
}

void Simulation::sample(const SensorInstance& s) {
  // samplers take the spec framed at set-up (namespaced frame_id) and this sensor's slot
  const SensorSpec& spec = s.spec;
  SensorSlot& slot = state_.sensors[static_cast<std::size_t>(s.slot)];
  const SimTime now = state_.time;
  // the robot's root link (base_link for the rescue robot, maybe base_footprint for a URDF robot)
  const auto root_frame = [&] { return frame_name(s.robot, world().robot(s.robot).spec.links[0].name); };
  switch (spec.type) {
    case SensorSpec::Type::lidar:
    case SensorSpec::Type::sonar:
      // post_step samples these itself, in parallel; this is the one-at-a-time way
      bus_.publish(s.topic, sample_rays(s, current_rays()));
      break;
    case SensorSpec::Type::imu: bus_.publish(s.topic, sample_imu(world(), state_, s.robot, spec, now, slot)); break;
    case SensorSpec::Type::odometry: {
      // odom -> root link on /tf from wheel odometry, unless ground truth gives it
      const msg::Odometry odom = odometry_message(world(), state_, s.robot, spec, now, root_frame());
      if (!options_.tf_from_ground_truth) {
        msg::TFMessage tf;
        tf.transforms.push_back(transform(now, odom.header.frame_id, odom.child_frame_id, odom.pose));
        bus_.publish(tf_topic_, std::move(tf));
      }
      bus_.publish(s.topic, odom);
      break;
    }
    case SensorSpec::Type::ground_truth: {
      bus_.publish(s.topic, sample_ground_truth(state_, s.robot, now));
      if (options_.tf_from_ground_truth || options_.publish_map_to_odom) {
        const GroundTruthTf which{frame_name(s.robot, "odom"), root_frame(), options_.tf_from_ground_truth, options_.publish_map_to_odom};
        bus_.publish(tf_topic_, ground_truth_tf(state_, s.robot, now, which));
      }
      break;
    }
    case SensorSpec::Type::joint_states: bus_.publish(s.topic, sample_joint_states(world(), state_, s.robot, now)); break;
    case SensorSpec::Type::contact: bus_.publish(s.topic, sample_contacts(state_, s.robot, spec, now)); break;
    case SensorSpec::Type::color_camera:
    case SensorSpec::Type::depth_camera:
    case SensorSpec::Type::thermal_camera:
      if (cameras_) cameras_->sample(world(), state_, s, slot);
      break;
  }
}

void Simulation::publish_tf_static() {
  // every sensor mount, and every fixed joint, relative to its link
  msg::TFMessage tf;
  for (std::size_t r = 0; r < world().robots.size(); ++r) {
    const RobotSpec& spec = world().robots[r].spec;
    const RobotIndex ri = RobotIndex::at(r);
    for (const auto& j : spec.joints) {
      if (j.type == JointSpec::Type::fixed)
        tf.transforms.push_back(transform(SimTime{}, frame_name(ri, j.parent), frame_name(ri, j.child), j.X_PJ));
    }
    for (const auto& s : spec.sensors) {
      if (s.frame_id.empty() || s.frame_id == s.link || !s.kind().mounted) continue;
      tf.transforms.push_back(transform(SimTime{}, frame_name(ri, s.link), frame_name(ri, s.frame_id), s.X_LS));
      if (s.is_camera()) {
        // optical axes in the body frame: x_O = -y_B, y_O = -z_B, z_O = x_B
        Eigen::Matrix3d R_BO;
        R_BO << 0, 0, 1, -1, 0, 0, 0, -1, 0;
        tf.transforms.push_back(transform(SimTime{}, frame_name(ri, s.frame_id), frame_name(ri, optical_frame(s.frame_id)),
                                          Pose3{Vec3::Zero(), Quat(R_BO)}));
      }
    }
  }
  bus_.publish(tf_static_topic_, std::move(tf));
}

void Simulation::publish_descriptions() {
  for (std::size_t r = 0; r < world().robots.size(); ++r) {
    if (description_topics_[r] != kNoTopic) bus_.publish(description_topics_[r], msg::String{world().robots[r].spec.description});
  }
}

void Simulation::publish_tf() {
  // moving joints: each child link relative to its parent at the current joint position
  msg::TFMessage tf;
  for (std::size_t r = 0; r < world().robots.size(); ++r) {
    const RobotSpec& spec = world().robots[r].spec;
    const RobotState& rs = state_.robots[r];
    for (std::size_t j = 0; j < spec.joints.size(); ++j) {
      const JointSpec& js = spec.joints[j];
      if (js.type == JointSpec::Type::fixed) continue;
      // a rotation about the axis, or for a prismatic joint a translation along it
      const Pose3 X = js.X_PJ * joint_motion(js, rs.q[j]);
      tf.transforms.push_back(transform(state_.time, frame_name(RobotIndex::at(r), js.parent), frame_name(RobotIndex::at(r), js.child), X));
    }
  }
  if (!tf.transforms.empty()) bus_.publish(tf_topic_, std::move(tf));
}

void Simulation::check_victims() {
  // one detector, picked at set-up (line of sight, or thermal images: those robots' victims are
  // recorded as their frames are delivered)
  victim_detector_->check(world(), state_, current_rays());
}

void Simulation::set_victim_detector(std::unique_ptr<VictimDetector> detector) {
  victim_detector_ = detector ? std::move(detector) : std::make_unique<LineOfSightDetector>();
}

void Simulation::flush_cameras() {
  if (cameras_) {
    cameras_->deliver(world(), state_, SimTime{std::numeric_limits<std::int64_t>::max()},
                      [this](TopicId topic, msg::Message m) { bus_.publish(topic, std::move(m)); });
  }
}

State Simulation::snapshot() {
  // a synchronisation point: the live engine is put into the same canonical state a restore of
  // this snapshot produces, so the run on from here and every restored run are bitwise equal
  physics_->restore(state_);
  return state_;
}

void Simulation::restore(const State& state) {
  // a state from before anything was spawned: what was spawned since goes first
  if (state.robots.size() == base_robots_ && state.dynamics.size() == base_dynamics_) remove_spawned();
  RS_DEMAND(state.robots.size() == state_.robots.size() && state.dynamics.size() == state_.dynamics.size() &&
                state.sensors.size() == state_.sensors.size() && state.victims.size() == state_.victims.size(),
            "Simulation::restore: the state is of another world");
  state_ = state;
  physics_->restore(state_);
  rays_current_ = false;
}

}  // namespace rescuesim
