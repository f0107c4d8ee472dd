#include "world/scenario/scenario_robots.h"

#include <cmath>

namespace rescuesim {

namespace {

constexpr double kDeg = M_PI / 180.0;

void read_noise(const YamlNode& n, const std::string& prefix, NoiseSpec& noise) {
  noise.stddev = n.number(prefix + "noise", noise.stddev, 0, 1e6);
  noise.bias = n.number(prefix + "bias", noise.bias, -1e6, 1e6);
  noise.bias_walk = n.number(prefix + "bias_walk", noise.bias_walk, 0, 1e6);
}

void read_ranges(const YamlNode& n, double& min_range, double& max_range) {
  min_range = n.number("min_range", min_range, 0, 1e4);
  max_range = n.number("max_range", max_range, 1e-3, 1e4);
  if (min_range >= max_range) {
    throw Error(n.where("min_range"), "min_range " + std::to_string(min_range) + " m must be below max_range " +
                                          std::to_string(max_range) + " m");
  }
}

/// Settings every sensor has: enabled, rate, topic, frame and mount pose.
void read_common(const YamlNode& n, SensorSpec& s) {
  s.enabled = n.boolean("enabled", s.enabled);
  s.rate = n.number("rate", s.rate, 1e-3, 10000);
  s.topic = n.string("topic", s.topic);
  s.frame_id = n.string("frame_id", s.frame_id);
  if (n.has("pose")) {
    const YamlNode p = n.map("pose");
    const Vec3 xyz(p.number("x", s.X_LS.p.x()), p.number("y", s.X_LS.p.y()), p.number("z", s.X_LS.p.z()));
    s.X_LS = Pose3::from_rpy(xyz, p.number("roll", 0) * kDeg, p.number("pitch", 0) * kDeg, p.number("yaw", 0) * kDeg);
    p.finish();
  }
}

void read_sensor(const YamlNode& n, SensorSpec& s) {
  read_common(n, s);
  switch (s.type) {
    case SensorSpec::Type::lidar: {
      LidarSpec& l = s.lidar;
      const double fov = n.number("fov", (l.max_angle - l.min_angle) / kDeg, 1e-3, 360);
      l.min_angle = -fov / 2 * kDeg;
      l.max_angle = fov / 2 * kDeg;
      l.samples = static_cast<int>(n.integer("samples", l.samples, 2, 100000));
      l.layers = static_cast<int>(n.integer("layers", l.layers, 1, 256));
      l.vertical_fov = n.number("vertical_fov", l.vertical_fov / kDeg, 0, 180) * kDeg;
      read_ranges(n, l.min_range, l.max_range);
      read_noise(n, "", l.noise);
      break;
    }
    case SensorSpec::Type::sonar: {
      SonarSpec& so = s.sonar;
      so.fov = n.number("fov", so.fov / kDeg, 1e-3, 179) * kDeg;
      so.rays = static_cast<int>(n.integer("rays", so.rays, 1, 64));
      so.max_incidence = n.number("max_incidence", so.max_incidence / kDeg, 0, 90) * kDeg;
      read_ranges(n, so.min_range, so.max_range);
      read_noise(n, "", so.noise);
      break;
    }
    case SensorSpec::Type::imu:
      read_noise(n, "gyro_", s.imu.gyro);
      read_noise(n, "accel_", s.imu.accel);
      read_noise(n, "orientation_", s.imu.orientation);
      break;
    case SensorSpec::Type::odometry:
      read_noise(n, "wheel_", s.odometry.wheel_noise);
      s.odometry.gyro_heading = n.boolean("gyro_heading", s.odometry.gyro_heading);
      read_noise(n, "gyro_", s.odometry.gyro);
      break;
    case SensorSpec::Type::color_camera:
    case SensorSpec::Type::depth_camera:
    case SensorSpec::Type::thermal_camera: {
      CameraSpec& c = s.camera;
      c.width = static_cast<int>(n.integer("width", c.width, 1, 8192));
      c.height = static_cast<int>(n.integer("height", c.height, 1, 8192));
      c.hfov = n.number("hfov", c.hfov / kDeg, 1e-3, 179.9) * kDeg;
      if (c.hfov <= 0) throw Error(n.where("hfov"), "field of view must be in (0, 180) degrees");
      read_ranges(n, c.min_range, c.max_range);
      read_noise(n, "", c.noise);
      c.blur_sigma = n.number("blur_sigma", c.blur_sigma, 0, 50);
      break;
    }
    case SensorSpec::Type::ground_truth:
    case SensorSpec::Type::joint_states:
    case SensorSpec::Type::contact: break;
  }
  n.finish();
}

}  // namespace

RobotConfig read_robot(const YamlNode& node, int index, const ModelMap& models) {
  RobotConfig c;
  c.name = node.string("name", index == 0 ? "robot" : "robot_" + std::to_string(index + 1));
  if (c.name.empty() || c.name.find_first_of("/ ") != std::string::npos) {
    throw Error(node.where("name"), "robot name '" + c.name + "' must be non-empty without '/' or spaces (it names topics)");
  }
  c.model = node.string("model", c.model);
  const auto it = models.find(c.model);
  if (it == models.end()) {
    std::string known;
    for (const auto& [k, v] : models) known += (known.empty() ? "" : ", ") + k;
    throw Error(node.where("model"), "unknown robot model '" + c.model + "' (known: " + known + ")");
  }
  c.spec = it->second;
  c.controller = node.choice("controller", c.controller, {"explorer", "wall_follower", "none"});
  if (node.has("start")) {
    const YamlNode s = node.map("start");
    c.start = Pose2{s.required_number("x"), s.required_number("y"), s.number("yaw", 0, -360, 360) * kDeg};
    s.finish();
  }
  if (node.has("head")) {
    const auto head = node.numbers("head", {}, c.spec.head_joints.size());
    for (std::size_t i = 0; i < head.size(); ++i) {
      JointSpec& j = c.spec.joints[static_cast<std::size_t>(c.spec.joint_index(c.spec.head_joints[i]))];
      const double q = head[i] * kDeg;
      if (q < j.lower || q > j.upper) {
        throw Error(node.where("head"), "head joint " + j.name + " at " + std::to_string(head[i]) + " degrees is outside its limits [" +
                                            std::to_string(j.lower / kDeg) + ", " + std::to_string(j.upper / kDeg) + "]");
      }
      j.initial = q;
    }
  }
  const YamlNode sensors = node.map("sensors");
  if (sensors.is_map()) {
    for (SensorSpec& s : c.spec.sensors) {
      if (sensors.has(s.name)) read_sensor(sensors.map(s.name), s);
    }
  }
  sensors.finish();
  node.finish();
  return c;
}

}  // namespace rescuesim
