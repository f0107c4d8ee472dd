#include "env_core.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/error.h"
#include "session/scenario_load.h"
#include "session/session.h"

namespace rescuesim::python {

namespace {

/// Copies an image's rows into a tightly packed buffer of `bytes` (rows of `row` bytes).
void copy_image(const msg::Image& m, std::uint8_t* out, std::size_t bytes, std::size_t row) {
  const std::size_t rows = std::min<std::size_t>(m.height, row > 0 ? bytes / row : 0);
  const std::size_t n = std::min<std::size_t>(row, m.step);
  for (std::size_t y = 0; y < rows && y * m.step + n <= m.data.size(); ++y) std::memcpy(out + y * row, m.data.data() + y * m.step, n);
}

}  // namespace

std::size_t ObsField::bytes() const {
  std::size_t n = item;
  for (std::size_t s : shape) n *= s;
  return n;
}

EnvCore::EnvCore(Scenario scenario, ModelMap models, EnvOptions options)
    : scenario_(std::move(scenario)), models_(std::move(models)), options_(std::move(options)) {
  if (!(options_.control_period > 0) || !std::isfinite(options_.control_period)) {
    throw Error("rescuesim.Env: control_period must be a positive number of seconds");
  }
  if (options_.max_time && !(*options_.max_time > 0 && std::isfinite(*options_.max_time))) {
    throw Error("rescuesim.Env: max_time must be a positive number of seconds");
  }
  if (!options_.controller.empty() && options_.controller != "explorer" && options_.controller != "wall_follower") {
    throw Error("rescuesim.Env: controller '" + options_.controller + "' is unknown (expected \"\", \"explorer\" or \"wall_follower\")");
  }
  period_ns_ = SimTime::from_seconds(options_.control_period).ns;
  build(scenario_.seed);

  // the observation layout, from the controlled robot's enabled sensors
  const RobotSpec& spec = session_->sim().world().robot(robot_).spec;
  max_linear_ = spec.drive.max_linear;
  max_angular_ = spec.drive.max_angular;
  ObsField sonar{"sonar", "float32", {0}, 4, ObsField::Kind::sonar, {}, {}};
  for (std::size_t i = 0; i < spec.sensors.size(); ++i) {
    const SensorSpec& s = spec.sensors[i];
    if (!s.enabled) continue;
    const int si = static_cast<int>(i);
    switch (s.type) {
      case SensorSpec::Type::lidar:
        // planar lasers publish LaserScan; multi-layer ones publish point clouds, not offered here
        if (s.lidar.layers == 1) {
          fields_.push_back({s.name, "float32", {static_cast<std::size_t>(s.lidar.samples)}, 4, ObsField::Kind::lidar, {si}, {}});
        }
        break;
      case SensorSpec::Type::sonar:
        sonar.sensors.push_back(si);
        break;
      case SensorSpec::Type::imu:
        fields_.push_back({s.name, "float64", {10}, 8, ObsField::Kind::imu, {si}, {}});
        break;
      case SensorSpec::Type::odometry:
        fields_.push_back({s.name, "float64", {5}, 8, ObsField::Kind::odometry, {si}, {}});
        break;
      case SensorSpec::Type::color_camera:
        if (options_.cameras) {
          fields_.push_back(
              {s.name, "uint8", {std::size_t(s.camera.height), std::size_t(s.camera.width), 3}, 1, ObsField::Kind::color, {si}, {}});
        }
        break;
      case SensorSpec::Type::depth_camera:
        if (options_.cameras) {
          const bool mm = s.camera.depth_encoding == "16UC1";
          fields_.push_back({s.name, mm ? "uint16" : "float32", {std::size_t(s.camera.height), std::size_t(s.camera.width)},
                             mm ? 2u : 4u, ObsField::Kind::depth, {si}, s.camera.depth_encoding});
        }
        break;
      case SensorSpec::Type::thermal_camera:
        if (options_.cameras) {
          fields_.push_back(
              {s.name, "uint16", {std::size_t(s.camera.height), std::size_t(s.camera.width)}, 2, ObsField::Kind::thermal, {si}, {}});
        }
        break;
      default:
        break;
    }
  }
  if (!sonar.sensors.empty()) {
    sonar.shape = {sonar.sensors.size()};
    fields_.push_back(sonar);
  }
  if (!options_.observations.empty()) {
    // only the observations asked for, in the order asked
    std::vector<ObsField> chosen;
    for (const auto& key : options_.observations) {
      const auto it = std::find_if(fields_.begin(), fields_.end(), [&](const ObsField& f) { return f.key == key; });
      if (it == fields_.end()) {
        std::string known;
        for (const auto& f : fields_) known += (known.empty() ? "" : ", ") + f.key;
        throw Error("rescuesim.Env: no observation '" + key + "' (available: " + known + (options_.cameras ? "" : "; cameras are off") +
                    ")");
      }
      chosen.push_back(*it);
    }
    fields_ = std::move(chosen);
  }
  own_.resize(fields_.size());
  for (std::size_t k = 0; k < fields_.size(); ++k) {
    own_[k].assign(fields_[k].bytes(), 0);
    buffers_.push_back(own_[k].data());
  }
  subscribe();
}

EnvCore::~EnvCore() = default;

void EnvCore::bind(const std::vector<std::uint8_t*>& buffers) {
  RS_DEMAND(buffers.size() == fields_.size(), "one buffer per observation field");
  for (std::size_t k = 0; k < fields_.size(); ++k) std::memcpy(buffers[k], buffers_[k], fields_[k].bytes());
  buffers_ = buffers;
  own_.clear();
  own_.shrink_to_fit();
}

void EnvCore::build(std::uint64_t seed) {
  ready_ = false;
  Scenario s = scenario_;
  reseed_scenario(s, seed, !options_.fixed_world);
  s.realtime = false;
  s.stop_when_all_found = false;
  // the controlled robot listens to the actions (unless a built-in controller is asked for);
  // the others keep the scenario's controllers
  if (s.robots.empty()) s.robots = robot_configs(s, build_world(s), models_);
  int r = 0;
  if (!options_.robot.empty()) {
    r = -1;
    for (std::size_t i = 0; i < s.robots.size(); ++i) {
      if (s.robots[i].name == options_.robot) r = static_cast<int>(i);
    }
    if (r < 0) throw Error({s.source_file, 0, "robots"}, "rescuesim.Env: the scenario has no robot named '" + options_.robot + "'");
  }
  s.robots[static_cast<std::size_t>(r)].controller = options_.controller.empty() ? "none" : options_.controller;
  max_time_ = options_.max_time ? *options_.max_time : s.duration;
  if (!std::isfinite(max_time_)) throw Error({s.source_file, 0, "duration"}, "rescuesim.Env: give max_time (the scenario runs forever)");
  SessionOptions so;
  so.cameras = options_.cameras;
  so.control = true;  // entities, teleports (bind_control.cpp); Python steps the run itself, so it never pauses
  session_.reset();  // the old simulation goes first: its camera service may hold the GL context
  session_ = std::make_unique<Session>(s, models_, so);
  start_ = std::make_unique<SessionSnapshot>(session_->snapshot());
  ++builds_;
  robot_ = RobotIndex::at(static_cast<std::size_t>(r));
  robot_name_ = s.robots[static_cast<std::size_t>(r)].name;
  seed_ = seed;
  fresh_ = true;
  done_ = false;
  steps_ = 0;
  found_.assign(session_->sim().state().victims.size(), 0);
  collisions_ = 0;
  new_victims_.clear();
}

void EnvCore::subscribe() {
  Simulation& sim = session_->sim();
  const RobotSpec& spec = sim.world().robot(robot_).spec;
  for (std::size_t k = 0; k < fields_.size(); ++k) {
    const ObsField& f = fields_[k];
    for (std::size_t j = 0; j < f.sensors.size(); ++j) {
      const SensorSpec& s = spec.sensors[static_cast<std::size_t>(f.sensors[j])];
      const std::string topic = sim.topic_name(robot_, s.topic);
      sim.bus().subscribe(topic, [this, k, j](const Topic&, const msg::Message& m) {
        const ObsField& f = fields_[k];
        std::uint8_t* out = buffers_[k];
        switch (f.kind) {
          case ObsField::Kind::lidar: {
            const auto& scan = std::get<msg::LaserScan>(m);
            std::memcpy(out, scan.ranges.data(), std::min(f.bytes(), scan.ranges.size() * sizeof(float)));
            break;
          }
          case ObsField::Kind::sonar: {
            const float range = std::get<msg::Range>(m).range;
            std::memcpy(out + j * sizeof(float), &range, sizeof range);
            break;
          }
          case ObsField::Kind::imu: {
            const auto& imu = std::get<msg::Imu>(m);
            const double v[10] = {imu.orientation.x(),      imu.orientation.y(),      imu.orientation.z(),      imu.orientation.w(),
                                  imu.angular_velocity.x(), imu.angular_velocity.y(), imu.angular_velocity.z(), imu.linear_acceleration.x(),
                                  imu.linear_acceleration.y(), imu.linear_acceleration.z()};
            std::memcpy(out, v, sizeof v);
            break;
          }
          case ObsField::Kind::odometry: {
            const auto& odom = std::get<msg::Odometry>(m);
            const Pose2 p = odom.pose.to_pose2();
            const double v[5] = {p.x, p.y, p.yaw, odom.twist.linear.x(), odom.twist.angular.z()};
            std::memcpy(out, v, sizeof v);
            break;
          }
          case ObsField::Kind::color:
          case ObsField::Kind::depth:
          case ObsField::Kind::thermal: {
            const std::size_t row = f.shape[1] * (f.shape.size() > 2 ? f.shape[2] : 1) * f.item;
            copy_image(std::get<msg::Image>(m), out, f.bytes(), row);
            break;
          }
        }
      });
    }
  }
}

void EnvCore::clear_buffers() {
  for (std::size_t k = 0; k < fields_.size(); ++k) std::memset(buffers_[k], 0, fields_[k].bytes());
}

void EnvCore::reset(std::uint64_t seed) {
  if (!session_ || seed != seed_) {
    build(seed);
    subscribe();
  } else if (!fresh_) {
    // the same seed: back to the start instead of building everything again
    session_->restore(*start_);
    done_ = false;
    steps_ = 0;
    std::fill(found_.begin(), found_.end(), 0);
    collisions_ = 0;
    new_victims_.clear();
  }
  clear_buffers();
  // the first step publishes every sensor's sample at t = 0
  session_->step_until(SimTime{1});
  fresh_ = false;
  ready_ = true;
  const State& s = session_->sim().state();
  for (std::size_t v = 0; v < s.victims.size(); ++v) found_[v] = s.victims[v].first_seen.ns >= 0;
  collisions_ = s.robot(robot_).collisions;
  done_ = session_->sim().in_trouble();
}

StepOutcome EnvCore::step(double linear, double angular) {
  if (!ready_) throw Error("rescuesim.Env.step: call reset() first");
  if (done_) throw Error("rescuesim.Env.step: the episode is over (terminated or truncated); call reset()");
  if (!std::isfinite(linear) || !std::isfinite(angular)) throw Error("rescuesim.Env.step: the action must be finite numbers");
  Simulation& sim = session_->sim();
  if (options_.controller.empty()) {
    msg::Twist t;
    t.linear.x() = linear;
    t.angular.z() = angular;
    sim.command_velocity(robot_, t);
  }
  ++steps_;
  const bool ok = session_->step_until(SimTime{period_ns_ * steps_});
  const State& s = sim.state();
  StepOutcome out;
  new_victims_.clear();
  int all_found = 0;
  for (std::size_t v = 0; v < s.victims.size(); ++v) {
    const bool seen = s.victims[v].first_seen.ns >= 0;
    if (seen && !found_[v] && s.victims[v].seen_by == robot_name_) new_victims_.push_back(sim.world().victims[v].name);
    found_[v] = seen;
    all_found += seen;
  }
  const int collisions = s.robot(robot_).collisions;
  out.reward = options_.victim_reward * static_cast<double>(new_victims_.size()) - options_.collision_penalty * (collisions - collisions_) -
               options_.time_penalty * options_.control_period;
  collisions_ = collisions;
  out.terminated = !ok || (!s.victims.empty() && all_found == static_cast<int>(s.victims.size()));
  out.truncated = !out.terminated && s.time.seconds() >= max_time_ - 1e-9;
  done_ = out.terminated || out.truncated;
  return out;
}

EpisodeInfo EnvCore::info() const {
  EpisodeInfo i;
  i.seed = seed_;
  i.steps = steps_;
  if (!session_) return i;
  const Simulation& sim = session_->sim();
  const State& s = sim.state();
  const RobotState& rs = s.robot(robot_);
  i.sim_time = s.time.seconds();
  i.victims_total = static_cast<int>(s.victims.size());
  for (const auto& v : s.victims) i.victims_found += v.first_seen.ns >= 0;
  i.collisions = rs.collisions;
  i.distance = rs.distance;
  i.coverage = session_->coverage();
  i.pose = rs.base.X_WB.to_pose2();
  i.new_victims = new_victims_;
  if (sim.in_trouble()) i.trouble = s.trouble.first;
  return i;
}

}  // namespace rescuesim::python
