#include "import/scenario/scenario_robots.h"
#include "import/sdf/sdf_import.h"

#include <algorithm>
#include <cmath>

#include "import/urdf/urdf_import.h"

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
      if (s.type == SensorSpec::Type::color_camera) {
        c.exposure = n.number("exposure", c.exposure, 1e-3, 1e3);
        c.auto_exposure = n.boolean("auto_exposure", c.auto_exposure);
        c.max_gain = n.number("max_gain", c.max_gain, 1, 1e4);
      }
      break;
    }
    case SensorSpec::Type::ground_truth:
    case SensorSpec::Type::joint_states:
    case SensorSpec::Type::contact: break;
  }
  n.finish();
}

/// The kind of sensor a `sensors:` list entry adds (its `type:`, named as sensor_type_name names it).
SensorSpec::Type sensor_type_of(const YamlNode& item) {
  using T = SensorSpec::Type;
  static const T kinds[] = {T::lidar, T::sonar, T::imu, T::color_camera, T::depth_camera, T::thermal_camera};
  std::vector<std::string> names;
  for (T t : kinds) names.push_back(sensor_type_name(t));
  const std::string name = item.choice("type", "", names);
  for (T t : kinds) {
    if (name == sensor_type_name(t)) return t;
  }
  return T::lidar;  // not reached: choice() accepts only the names above
}

/// `sensors:` as a list: each entry changes the sensor of that name, or adds one of `type` on
/// `link` (URDF robots name their links; frames are the link's unless a pose is given).
void read_sensor_list(const YamlNode& node, RobotSpec& spec) {
  const auto items = node.sequence("sensors");
  for (std::size_t i = 0; i < items.size(); ++i) {
    const YamlNode& item = items[i];
    const std::string name = item.string("name", "");
    SensorSpec* existing = name.empty() ? nullptr : spec.find_sensor(name);
    if (existing) {
      item.string("type", "");
      item.string("link", "");
      read_sensor(item, *existing);
      continue;
    }
    SensorSpec s;
    s.type = sensor_type_of(item);
    const std::string kind = sensor_type_name(s.type);
    int same = 0;
    for (const auto& x : spec.sensors) same += x.type == s.type;
    s.name = name.empty() ? (same == 0 ? kind : kind + "_" + std::to_string(same + 1)) : name;
    s.link = item.string("link", spec.links.front().name);
    if (spec.link_index(s.link) < 0) {
      std::string known;
      for (const auto& l : spec.links) known += (known.empty() ? "" : ", ") + l.name;
      throw Error(item.where("link"), "sensor '" + s.name + "': '" + s.link + "' is not a link of the robot (links: " + known + ")");
    }
    s.frame_id = item.has("pose") ? s.name : s.link;
    switch (s.type) {
      case SensorSpec::Type::lidar: s.topic = same == 0 ? "scan" : s.name + "/scan"; break;
      case SensorSpec::Type::sonar: s.topic = "sonar/" + s.name; break;
      case SensorSpec::Type::imu: s.topic = same == 0 ? "imu/data" : s.name + "/data"; break;
      case SensorSpec::Type::color_camera: s.topic = s.name + "/image_raw"; break;
      case SensorSpec::Type::depth_camera: s.topic = s.name + "/depth/image_raw"; break;
      default: s.topic = s.name + "/image_raw"; break;
    }
    read_sensor(item, s);
    spec.sensors.push_back(s);
  }
}

/// `lamps:`: spot lamps on links (docs/environment.md, "Robot lamps"). An item named as an existing lamp
/// (the built-in models' `head_lamp`) changes it; any other is added, by default on the base link
/// shining forwards.
void read_lamp_list(const YamlNode& node, RobotSpec& spec) {
  const auto items = node.sequence("lamps");
  for (std::size_t i = 0; i < items.size(); ++i) {
    const YamlNode& item = items[i];
    const std::string name = item.string("name", spec.lights.empty() ? "lamp" : "lamp_" + std::to_string(spec.lights.size() + 1));
    auto it = std::find_if(spec.lights.begin(), spec.lights.end(), [&](const RobotLightSpec& l) { return l.name == name; });
    RobotLightSpec lamp;
    if (it != spec.lights.end()) lamp = *it;
    lamp.name = name;
    lamp.link = item.string("link", it != spec.lights.end() ? lamp.link : spec.links.front().name);
    if (spec.link_index(lamp.link) < 0) {
      std::string known;
      for (const auto& l : spec.links) known += (known.empty() ? "" : ", ") + l.name;
      throw Error(item.where("link"), "lamp '" + name + "': '" + lamp.link + "' is not a link of the robot (links: " + known + ")");
    }
    if (item.has("pose")) {
      const YamlNode p = item.map("pose");
      const Vec3 xyz(p.number("x", 0), p.number("y", 0), p.number("z", 0));
      lamp.X_LF = Pose3::from_rpy(xyz, p.number("roll", 0) * kDeg, p.number("pitch", 0) * kDeg, p.number("yaw", 0) * kDeg);
      p.finish();
    }
    if (item.has("color")) {
      const auto c = item.numbers("color", {}, 3);
      for (double v : c) {
        if (!(v >= 0 && v <= 1)) throw Error(item.where("color"), "lamp '" + name + "': color components are linear RGB in [0, 1]");
      }
      lamp.color = {c[0], c[1], c[2]};
    }
    lamp.intensity = item.number("intensity", lamp.intensity, 0, 1e6);
    lamp.range = item.number("range", lamp.range, 1e-3, 1e4);
    lamp.cone = item.number("cone", lamp.cone / kDeg, 1e-3, 90) * kDeg;
    lamp.inner_cone = item.number("inner_cone", std::min(lamp.inner_cone, lamp.cone) / kDeg, 0, 90) * kDeg;
    if (lamp.inner_cone > lamp.cone) {
      throw Error(item.where("inner_cone"), "lamp '" + name + "': inner_cone " + message_number(lamp.inner_cone / kDeg) +
                                                 " degrees is wider than its cone, " + message_number(lamp.cone / kDeg));
    }
    item.finish();
    if (it != spec.lights.end()) *it = lamp;
    else spec.lights.push_back(lamp);
  }
}

/// `drive:`: a differential (skid-steer with several wheels a side) drive on named joints.
void read_drive(const YamlNode& d, RobotSpec& spec) {
  d.choice("type", "diff_drive", {"diff_drive", "skid_steer"});
  const auto left = d.strings("left", spec.drive.left_wheels), right = d.strings("right", spec.drive.right_wheels);
  const double radius = d.number("wheel_radius", 0, 0, 10), separation = d.number("wheel_separation", 0, 0, 100);
  if (d.has("left") || d.has("right") || radius > 0 || separation > 0)
    configure_diff_drive(spec, left, right, radius, separation, d.where());
  DriveSpec& dr = spec.drive;
  dr.max_linear = d.number("max_linear", dr.max_linear, 1e-3, 100);
  dr.max_angular = d.number("max_angular", dr.max_angular, 1e-3, 100);
  dr.max_linear_accel = d.number("max_linear_accel", dr.max_linear_accel, 1e-3, 1000);
  dr.max_angular_accel = d.number("max_angular_accel", dr.max_angular_accel, 1e-3, 1000);
  dr.track_multiplier = d.number("track_multiplier", dr.track_multiplier, 0.1, 10);
  d.finish();
}

/// The collision settings a `urdf:` or `sdf:` robot entry may give, into its importer's options.
template <class Options>
void read_collision_settings(const YamlNode& node, Options& o) {
  const std::string mode = node.choice("collision", "auto", {"auto", "hull", "decompose"});
  o.collision = mode == "hull" ? CollisionMode::hull : mode == "decompose" ? CollisionMode::decompose : CollisionMode::automatic;
  o.hull_vertices = static_cast<int>(node.integer("hull_vertices", o.hull_vertices, 4, 4096));
}

/// `urdf:`: the robot's own description, with its collision settings.
RobotSpec read_urdf_robot(const YamlNode& node, const RobotReadContext& context, RobotConfig& c) {
  UrdfOptions o;
  o.resolver = ResourceResolver(context.resource_paths);
  read_collision_settings(node, o);
  const std::string uri = node.string("urdf", "");
  const std::filesystem::path file = o.resolver.resolve(uri, {context.file, node.where("urdf").line, node.path() + ".urdf"});
  UrdfRobot u = load_urdf(file, o);
  c.urdf = file.string();
  c.diagnostics = u.diagnostics;
  return u.spec;
}

/// `sdf:`: a robot from an SDF <model> (a model:// URI, a model folder or an .sdf file).
RobotSpec read_sdf_robot(const YamlNode& node, const RobotReadContext& context, RobotConfig& c) {
  SdfOptions o;
  o.resolver = ResourceResolver(context.resource_paths);
  read_collision_settings(node, o);
  const std::string uri = node.string("sdf", "");
  SdfRobot r = load_sdf_robot(uri, o, {context.file, node.where("sdf").line, node.path() + ".sdf"});
  c.sdf = r.spec.source_file;
  c.diagnostics = r.diagnostics;
  return r.spec;
}

}  // namespace

RobotConfig read_robot(const YamlNode& node, int index, const ModelMap& models, const RobotReadContext& context) {
  RobotConfig c;
  c.name = node.string("name", index == 0 ? "robot" : "robot_" + std::to_string(index + 1));
  if (c.name.empty() || c.name.find_first_of("/ ") != std::string::npos) {
    throw Error(node.where("name"), "robot name '" + c.name + "' must be non-empty without '/' or spaces (it names topics)");
  }
  if (node.has("urdf") && node.has("sdf")) throw Error(node.where("sdf"), "give either urdf or sdf, not both");
  if (node.has("urdf") || node.has("sdf")) {
    const char* kind = node.has("urdf") ? "urdf" : "sdf";
    if (node.has("model")) {
      throw Error(node.where("model"), std::string("give either model (a built-in robot) or ") + kind + " (your own), not both");
    }
    c.spec = node.has("urdf") ? read_urdf_robot(node, context, c) : read_sdf_robot(node, context, c);
    c.model = std::string(kind) + ":" + c.spec.model + ":" + c.name;
    c.spec.model = c.model;
  } else {
    c.model = node.string("model", c.model);
    const auto it = models.find(c.model);
    if (it == models.end()) {
      std::string known;
      for (const auto& [k, v] : models) known += (known.empty() ? "" : ", ") + k;
      throw Error(node.where("model"), "unknown robot model '" + c.model + "' (known: " + known + "; or give urdf: a file of your own)");
    }
    c.spec = it->second;
  }
  if (node.has("drive")) {
    read_drive(node.map("drive"), c.spec);
    add_standard_sensors(c.spec);
  }
  c.controller = node.choice("controller", c.controller, {"explorer", "wall_follower", "none"});
  if (node.has("lamps")) {
    if (!node.has_sequence("lamps")) throw Error(node.where("lamps"), "lamps: expected a list of lamps (each with link, pose, cone, ...)");
    read_lamp_list(node, c.spec);
  }
  if (node.has("lights")) {
    if (c.spec.lights.empty()) throw Error(node.where("lights"), "robot model '" + c.model + "' has no lamps to switch on");
    c.spec.lights_on = node.boolean("lights", false);
  }
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
  if (node.has_sequence("sensors")) {
    read_sensor_list(node, c.spec);
  } else {
    const YamlNode sensors = node.map("sensors");
    if (sensors.is_map()) {
      for (SensorSpec& s : c.spec.sensors) {
        if (sensors.has(s.name)) read_sensor(sensors.map(s.name), s);
      }
    }
    sensors.finish();
  }
  node.finish();
  return c;
}

RobotConfig read_robot_yaml(const std::string& yaml_text, const std::string& file, const ModelMap& models,
                            const std::vector<std::filesystem::path>& resource_paths) {
  const YamlNode node = YamlNode::parse(yaml_text, file);
  if (!node.is_map()) throw Error({file, 1, "robot"}, "expected a robot as a map (model: or urdf: or sdf:, name:, sensors:, ...)");
  return read_robot(node, 0, models, {file, resource_paths});
}

}  // namespace rescuesim
