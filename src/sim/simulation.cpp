#include "sim/simulation.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "robots/drive_controller.h"
#include "sensors/imu.h"
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

bool is_camera(SensorSpec::Type t) {
  return t == SensorSpec::Type::color_camera || t == SensorSpec::Type::depth_camera || t == SensorSpec::Type::thermal_camera;
}

const char* topic_type(const SensorSpec& s) {
  switch (s.type) {
    case SensorSpec::Type::lidar: return s.lidar.layers > 1 ? "sensor_msgs/PointCloud2" : "sensor_msgs/LaserScan";
    case SensorSpec::Type::sonar: return "sensor_msgs/Range";
    case SensorSpec::Type::imu: return "sensor_msgs/Imu";
    case SensorSpec::Type::odometry: return "nav_msgs/Odometry";
    case SensorSpec::Type::ground_truth: return "geometry_msgs/PoseStamped";
    case SensorSpec::Type::joint_states: return "sensor_msgs/JointState";
    case SensorSpec::Type::contact: return "rescuesim_msgs/Contacts";
    case SensorSpec::Type::color_camera:
    case SensorSpec::Type::depth_camera:
    case SensorSpec::Type::thermal_camera: return "sensor_msgs/Image";
  }
  return "";
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

Simulation::Simulation(World world, const SimOptions& options) : world_(std::move(world)), options_(options) {
  physics_ = std::make_unique<Physics>(world_, options_.physics);
  rays_ = std::make_unique<RayScene>(world_);
  physics_->init_state(state_);
  state_.victims.assign(world_.victims.size(), VictimState{});
  for (auto& r : state_.robots) r.odom = Pose2{};
  setup_topics();
}

Simulation::~Simulation() = default;

bool Simulation::namespaced() const {
  switch (options_.namespacing) {
    case Namespacing::always: return true;
    case Namespacing::never: return false;
    case Namespacing::automatic: return world_.robots.size() > 1;
  }
  return false;
}

std::string Simulation::topic_name(int robot, const std::string& relative) const {
  if (!relative.empty() && relative[0] == '/') return relative;
  return namespaced() ? "/" + world_.robots[static_cast<std::size_t>(robot)].name + "/" + relative : "/" + relative;
}

std::string Simulation::frame_name(int robot, const std::string& frame) const {
  if (frame == "map" || frame.empty()) return frame;
  return namespaced() ? world_.robots[static_cast<std::size_t>(robot)].name + "/" + frame : frame;
}

int Simulation::robot_index(const std::string& name) const {
  for (std::size_t r = 0; r < world_.robots.size(); ++r) {
    if (world_.robots[r].name == name) return static_cast<int>(r);
  }
  return -1;
}

void Simulation::setup_topics() {
  clock_topic_ = bus_.advertise("/clock", "rosgraph_msgs/Clock", options_.clock_rate > 0 ? options_.clock_rate : 1.0 / dt());
  tf_topic_ = bus_.advertise("/tf", "tf2_msgs/TFMessage", options_.tf_rate);
  tf_static_topic_ = bus_.advertise("/tf_static", "tf2_msgs/TFMessage", 0, true);
  // a robot loaded from a description (URDF) offers it, latched, as robot_state_publisher does
  description_topics_.assign(world_.robots.size(), -1);
  for (std::size_t r = 0; r < world_.robots.size(); ++r) {
    if (world_.robots[r].spec.description.empty()) continue;
    const int ri = static_cast<int>(r);
    description_topics_[r] = bus_.advertise(topic_name(ri, "robot_description"), "std_msgs/String", 0, true, ri);
  }
  // one random stream and one schedule per sensor, in robot and spec order
  for (std::size_t r = 0; r < world_.robots.size(); ++r) {
    const RobotInstance& robot = world_.robots[r];
    for (std::size_t i = 0; i < robot.spec.sensors.size(); ++i) {
      const SensorSpec& spec = robot.spec.sensors[i];
      if (!spec.enabled) continue;
      SensorInstance s;
      s.robot = static_cast<int>(r);
      s.index = static_cast<int>(i);
      s.slot = static_cast<int>(state_.sensors.size());
      s.period = period_of(spec.rate);
      // images are in an optical frame (z forward, x right, y down) beside the camera's body frame (REP-103)
      s.frame_id = frame_name(s.robot, is_camera(spec.type) ? optical_frame(spec.frame_id) : spec.frame_id);
      const std::string topic = topic_name(s.robot, spec.topic);
      s.topic = bus_.advertise(topic, topic_type(spec), spec.rate, false, s.robot);
      if (is_camera(spec.type)) {
        const std::string base = topic.substr(0, topic.rfind('/'));
        s.info_topic = bus_.advertise(base + "/camera_info", "sensor_msgs/CameraInfo", spec.rate, false, s.robot);
        if (spec.type == SensorSpec::Type::depth_camera && spec.camera.point_cloud) {
          s.extra_topic = bus_.advertise(base + "/points", "sensor_msgs/PointCloud2", spec.rate, false, s.robot);
        }
        if (spec.type == SensorSpec::Type::thermal_camera) {
          s.extra_topic = bus_.advertise(base + "/image_mono8", "sensor_msgs/Image", spec.rate, false, s.robot);
        }
      }
      SensorSlot slot;
      slot.rng = Rng(options_.seed, "sensor/" + robot.name + "/" + spec.name);
      slot.next_due = SimTime{0};
      state_.sensors.push_back(slot);
      sensors_.push_back(s);
    }
  }
}

bool Simulation::command_velocity(int robot, const msg::Twist& t) {
  if (robot < 0 || robot >= static_cast<int>(world_.robots.size())) return false;
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(t.linear[i]) || !std::isfinite(t.angular[i])) return false;
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
  return true;
}

std::uint64_t Simulation::velocity_commands() const {
  std::lock_guard lock(commands_mutex_);
  return velocity_commands_;
}

bool Simulation::wait_for_velocity_commands(std::uint64_t count, std::chrono::duration<double> timeout) {
  std::unique_lock lock(commands_mutex_);
  return command_arrived_.wait_for(lock, timeout, [&] { return velocity_commands_ >= count; });
}

bool Simulation::command_head(int robot, const std::vector<double>& positions) {
  if (robot < 0 || robot >= static_cast<int>(world_.robots.size())) return false;
  if (positions.size() != world_.robots[static_cast<std::size_t>(robot)].spec.head_joints.size()) return false;
  for (double p : positions) {
    if (!std::isfinite(p)) return false;
  }
  Command c;
  c.robot = robot;
  c.kind = Command::Kind::head;
  c.values = positions;
  std::lock_guard lock(commands_mutex_);
  commands_.push_back(std::move(c));
  return true;
}

bool Simulation::command_joints(int robot, const msg::JointState& command, std::string* why) {
  const auto refuse = [&](std::string text) {
    if (why) *why = std::move(text);
    return false;
  };
  if (robot < 0 || robot >= static_cast<int>(world_.robots.size())) return refuse("no robot " + std::to_string(robot));
  const RobotSpec& spec = world_.robots[static_cast<std::size_t>(robot)].spec;
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
  return true;
}

std::size_t Simulation::discard_commands() {
  std::lock_guard lock(commands_mutex_);
  const std::size_t n = commands_.size();
  commands_.clear();
  return n;
}

void Simulation::pre_step() {
  // commands queued since the last step, in arrival order
  std::vector<Command> pending;
  {
    std::lock_guard lock(commands_mutex_);
    pending.swap(commands_);
  }
  for (const auto& c : pending) {
    RobotState& rs = state_.robots[static_cast<std::size_t>(c.robot)];
    switch (c.kind) {
      case Command::Kind::velocity:
        rs.cmd_linear = c.twist.linear;
        rs.cmd_angular = c.twist.angular;
        rs.cmd_time = state_.time;
        break;
      case Command::Kind::head: rs.head_target = c.values; break;
      case Command::Kind::joints:
        // joints the command does not name keep their targets
        rs.joint_target.resize(world_.robots[static_cast<std::size_t>(c.robot)].spec.joints.size(), 0.0);
        for (std::size_t i = 0; i < c.joints.size(); ++i) rs.joint_target[c.joints[i]] = c.values[i];
        break;
    }
  }
  for (std::size_t r = 0; r < world_.robots.size(); ++r) {
    update_drive(world_.robots[r].spec, state_.robots[r], state_.time, dt());
    update_head(world_.robots[r].spec, state_.robots[r]);
  }
}

void Simulation::step() {
  if (in_trouble()) return;
  if (!started_) {
    started_ = true;
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
  for (std::size_t r = 0; r < state_.robots.size(); ++r) state_.robots[r].distance += (state_.robots[r].base.X_WB.p - before[r]).head<2>().norm();
  // wheel odometry integrates every step, whatever rate it publishes at
  for (const auto& s : sensors_) {
    const SensorSpec& spec = world_.robots[static_cast<std::size_t>(s.robot)].spec.sensors[static_cast<std::size_t>(s.index)];
    if (spec.type == SensorSpec::Type::odometry) integrate_odometry(world_, state_, s.robot, spec, dt(), state_.sensors[static_cast<std::size_t>(s.slot)]);
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
  if (now >= next_clock_) {
    bus_.publish(clock_topic_, msg::Clock{now});
    next_clock_ = options_.clock_rate > 0 ? next_clock_ + period_of(options_.clock_rate) : now;
    if (options_.clock_rate <= 0) next_clock_ = now + SimTime{1};
  }
  for (const auto& s : sensors_) {
    SensorSlot& slot = state_.sensors[static_cast<std::size_t>(s.slot)];
    if (now < slot.next_due) continue;
    sample(s);
    ++slot.count;
    // the next due time keeps the nominal grid, even if a step overshot this one
    while (slot.next_due <= now) slot.next_due += s.period;
  }
  if (now >= next_tf_) {
    publish_tf();
    while (next_tf_ <= now) next_tf_ += period_of(options_.tf_rate);
  }
  if (cameras_) cameras_->deliver(world_, state_, now, [this](int topic, msg::Message m) { bus_.publish(topic, std::move(m)); });
  if (now >= next_victim_check_ && !world_.victims.empty()) {
    check_victims();
    while (next_victim_check_ <= now) next_victim_check_ += period_of(options_.victim_check_rate);
  }
}

void Simulation::sample(const SensorInstance& s) {
  const RobotInstance& robot = world_.robots[static_cast<std::size_t>(s.robot)];
  const SensorSpec& spec = robot.spec.sensors[static_cast<std::size_t>(s.index)];
  SensorSlot& slot = state_.sensors[static_cast<std::size_t>(s.slot)];
  const RobotState& rs = state_.robots[static_cast<std::size_t>(s.robot)];
  const SimTime now = state_.time;
  SensorSpec framed = spec;
  framed.frame_id = s.frame_id;
  auto rays = [&]() -> const RayScene& {
    if (!rays_current_) {
      rays_->update(state_);
      rays_current_ = true;
    }
    return *rays_;
  };
  switch (spec.type) {
    case SensorSpec::Type::lidar:
      if (spec.lidar.layers > 1) {
        bus_.publish(s.topic, sample_lidar_cloud(world_, state_, rays(), s.robot, framed, now, slot.rng));
      } else {
        bus_.publish(s.topic, sample_lidar(world_, state_, rays(), s.robot, framed, now, slot.rng));
      }
      break;
    case SensorSpec::Type::sonar: bus_.publish(s.topic, sample_sonar(world_, state_, rays(), s.robot, framed, now, slot.rng)); break;
    case SensorSpec::Type::imu: bus_.publish(s.topic, sample_imu(world_, state_, s.robot, framed, now, slot)); break;
    case SensorSpec::Type::odometry: {
      // the child frame is the robot's root link: base_link for the rescue robot, maybe base_footprint for a URDF robot
      const msg::Odometry odom = odometry_message(world_, state_, s.robot, framed, now, frame_name(s.robot, robot.spec.links[0].name));
      if (!options_.tf_from_ground_truth) {
        msg::TFMessage tf;
        tf.transforms.push_back(transform(now, odom.header.frame_id, odom.child_frame_id, odom.pose));
        bus_.publish(tf_topic_, std::move(tf));
      }
      bus_.publish(s.topic, odom);
      break;
    }
    case SensorSpec::Type::ground_truth: {
      msg::PoseStamped p;
      p.header = {now, "map"};
      p.pose = rs.base.X_WB;
      bus_.publish(s.topic, std::move(p));
      msg::TFMessage tf;
      if (options_.tf_from_ground_truth) {
        tf.transforms.push_back(transform(now, frame_name(s.robot, "odom"), frame_name(s.robot, robot.spec.links[0].name), rs.base.X_WB));
      }
      if (options_.publish_map_to_odom) {
        // map -> odom such that map -> odom -> root link is the true pose
        const Pose3 X_OB = options_.tf_from_ground_truth ? rs.base.X_WB : Pose3::from_pose2(rs.odom);
        tf.transforms.push_back(transform(now, "map", frame_name(s.robot, "odom"), rs.base.X_WB * X_OB.inverse()));
      }
      if (!tf.transforms.empty()) bus_.publish(tf_topic_, std::move(tf));
      break;
    }
    case SensorSpec::Type::joint_states: {
      msg::JointState js;
      js.header = {now, ""};
      for (std::size_t j = 0; j < robot.spec.joints.size(); ++j) {
        if (robot.spec.joints[j].type == JointSpec::Type::fixed) continue;
        js.name.push_back(robot.spec.joints[j].name);
        js.position.push_back(rs.q[j]);
        js.velocity.push_back(rs.qd[j]);
        js.effort.push_back(rs.effort[j]);
      }
      bus_.publish(s.topic, std::move(js));
      break;
    }
    case SensorSpec::Type::contact: {
      msg::Contacts c;
      c.header.stamp = now;
      c.header.frame_id = framed.frame_id;
      c.touching = rs.touching;
      bus_.publish(s.topic, std::move(c));
      break;
    }
    case SensorSpec::Type::color_camera:
    case SensorSpec::Type::depth_camera:
    case SensorSpec::Type::thermal_camera:
      if (cameras_) cameras_->sample(world_, state_, s, slot);
      break;
  }
}

void Simulation::publish_tf_static() {
  // every sensor mount, and every fixed joint, relative to its link
  msg::TFMessage tf;
  for (std::size_t r = 0; r < world_.robots.size(); ++r) {
    const RobotSpec& spec = world_.robots[r].spec;
    const int ri = static_cast<int>(r);
    for (const auto& j : spec.joints) {
      if (j.type == JointSpec::Type::fixed) tf.transforms.push_back(transform(SimTime{}, frame_name(ri, j.parent), frame_name(ri, j.child), j.X_PJ));
    }
    for (const auto& s : spec.sensors) {
      if (s.frame_id.empty() || s.frame_id == s.link || s.type == SensorSpec::Type::odometry || s.type == SensorSpec::Type::ground_truth) continue;
      tf.transforms.push_back(transform(SimTime{}, frame_name(ri, s.link), frame_name(ri, s.frame_id), s.X_LS));
      if (is_camera(s.type)) {
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
  for (std::size_t r = 0; r < world_.robots.size(); ++r) {
    if (description_topics_[r] >= 0) bus_.publish(description_topics_[r], msg::String{world_.robots[r].spec.description});
  }
}

void Simulation::publish_tf() {
  // moving joints: each child link relative to its parent at the current joint position
  msg::TFMessage tf;
  for (std::size_t r = 0; r < world_.robots.size(); ++r) {
    const RobotSpec& spec = world_.robots[r].spec;
    const RobotState& rs = state_.robots[r];
    for (std::size_t j = 0; j < spec.joints.size(); ++j) {
      const JointSpec& js = spec.joints[j];
      if (js.type == JointSpec::Type::fixed) continue;
      // a rotation about the axis, or for a prismatic joint a translation along it
      const Pose3 X = js.X_PJ * joint_motion(js, rs.q[j]);
      tf.transforms.push_back(transform(state_.time, frame_name(static_cast<int>(r), js.parent), frame_name(static_cast<int>(r), js.child), X));
    }
  }
  if (!tf.transforms.empty()) bus_.publish(tf_topic_, std::move(tf));
}

void Simulation::check_victims() {
  if (!rays_current_) {
    rays_->update(state_);
    rays_current_ = true;
  }
  for (std::size_t r = 0; r < world_.robots.size(); ++r) {
    const RobotSpec& spec = world_.robots[r].spec;
    // a victim is seen when it is in the thermal camera's view, in range, and not hidden
    const SensorSpec* cam = nullptr;
    for (const auto& s : spec.sensors) {
      if (s.type == SensorSpec::Type::thermal_camera) cam = &s;
    }
    // with rendered cameras, victims are found in the thermal images instead
    if (!cam || (cameras_ && cameras_->detects_victims(static_cast<int>(r)))) continue;
    const int link = spec.link_index(cam->link);
    const Pose3 X_WC = state_.robots[r].X_WL[static_cast<std::size_t>(link)] * cam->X_LS;
    const double tan_h = std::tan(cam->camera.hfov / 2);
    const double tan_v = tan_h * cam->camera.height / cam->camera.width;
    for (std::size_t v = 0; v < world_.victims.size(); ++v) {
      VictimState& vs = state_.victims[v];
      if (vs.first_seen.ns >= 0) continue;
      for (int part : world_.victims[v].parts) {
        const Vec3 p_W = world_.statics[static_cast<std::size_t>(part)].X_WO.p;
        const Vec3 p_C = X_WC.inverse() * p_W;
        if (p_C.x() <= cam->camera.min_range || p_C.x() > cam->camera.max_range) continue;
        if (std::abs(p_C.y()) > tan_h * p_C.x() || std::abs(p_C.z()) > tan_v * p_C.x()) continue;
        const Vec3 d = p_W - X_WC.p;
        Ray ray{X_WC.p, d.normalized(), static_cast<float>(d.norm() + 0.05)};
        RayHit hit;
        rays_->cast({&ray, 1}, {&hit, 1}, static_cast<int>(r));
        if (hit.source == RayHit::Source::static_object && world_.statics[static_cast<std::size_t>(hit.index)].victim == static_cast<int>(v)) {
          vs.first_seen = state_.time;
          vs.seen_by = world_.robots[r].name;
          break;
        }
      }
    }
  }
}

void Simulation::flush_cameras() {
  if (cameras_) {
    cameras_->deliver(world_, state_, SimTime{std::numeric_limits<std::int64_t>::max()},
                      [this](int topic, msg::Message m) { bus_.publish(topic, std::move(m)); });
  }
}

void Simulation::restore(const State& state) {
  state_ = state;
  physics_->restore(state_);
  rays_current_ = false;
}

}  // namespace rescuesim
