// <gazebo> extensions of a URDF: the drive plugin, sensors, and a warning for everything else
// that rescuesim does not honour.
#include <cmath>
#include <set>

#include "import/urdf/urdf_detail.h"

namespace rescuesim::urdf_detail {

namespace {

using tinyxml2::XMLElement;

std::string trimmed(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n"), t = s.find_last_not_of(" \t\r\n");
  return b == std::string::npos ? "" : s.substr(b, t - b + 1);
}

/// Text of a child element (the first of several names that is present), or "".
std::string child_text(const XMLElement* e, std::initializer_list<const char*> names) {
  for (const char* n : names) {
    const XMLElement* c = e->FirstChildElement(n);
    if (c && c->GetText()) return trimmed(c->GetText());
  }
  return "";
}

/// A number from a child element, or `fallback` when absent.
double child_number(const XMLElement* e, std::initializer_list<const char*> names, double fallback, const XmlIndex& index) {
  const std::string t = child_text(e, names);
  if (t.empty()) return fallback;
  for (const char* n : names) {
    if (const XMLElement* c = e->FirstChildElement(n)) return numbers_of(t.c_str(), 1, index, c, std::string("<") + n + ">")[0];
  }
  return fallback;
}

/// A whole count from a child element, in [lo, hi] (checked before it becomes an int).
int child_count(const XMLElement* e, const char* name, int fallback, int lo, int hi, const XmlIndex& index, const std::string& sensor) {
  const double v = child_number(e, {name}, fallback, index);
  if (!(v >= lo && v <= hi) || v != std::floor(v)) {
    throw Error(index.at(e->FirstChildElement(name)), "sensor '" + sensor + "': <" + name + "> must be a whole number in [" +
                                                          std::to_string(lo) + ", " + std::to_string(hi) + "], got " + std::to_string(v));
  }
  return static_cast<int>(v);
}

/// A path of child elements, e.g. {"ray", "scan", "horizontal"}; nullptr when any is missing.
const XMLElement* path(const XMLElement* e, std::initializer_list<const char*> names) {
  for (const char* n : names) {
    if (!e) return nullptr;
    e = e->FirstChildElement(n);
  }
  return e;
}

/// Every text of repeated child elements of these names, in order, trimmed (ROS 2 diff drive
/// repeats <left_joint> for each wheel pair).
std::vector<std::string> all_texts(const XMLElement* e, std::initializer_list<const char*> names) {
  std::vector<std::string> out;
  for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    for (const char* n : names) {
      if (std::string(c->Name()) == n && c->GetText()) out.push_back(trimmed(c->GetText()));
    }
  }
  return out;
}

const std::set<std::string> kDiffDrive{"libgazebo_ros_diff_drive.so", "libgazebo_ros_skid_steer_drive.so"};
/// Plugins whose work rescuesim does by itself (joint states, ground truth, sensor outputs).
const std::set<std::string> kCovered{"libgazebo_ros_joint_state_publisher.so", "libgazebo_ros_p3d.so",
                                     "libgazebo_ros_laser.so", "libgazebo_ros_gpu_laser.so", "libgazebo_ros_ray_sensor.so",
                                     "libgazebo_ros_camera.so", "libgazebo_ros_depth_camera.so", "libgazebo_ros_openni_kinect.so",
                                     "libgazebo_ros_multicamera.so", "libgazebo_ros_imu.so", "libgazebo_ros_imu_sensor.so"};

void read_drive_plugin(const XMLElement* plugin, const std::string& filename, const XmlIndex& index, UrdfRobot& out) {
  std::vector<std::string> left = all_texts(plugin, {"leftJoint", "left_joint", "leftFrontJoint", "leftRearJoint"});
  std::vector<std::string> right = all_texts(plugin, {"rightJoint", "right_joint", "rightFrontJoint", "rightRearJoint"});
  const double separation = child_number(plugin, {"wheelSeparation", "wheel_separation"}, 0, index);
  const double diameter = child_number(plugin, {"wheelDiameter", "wheel_diameter"}, 0, index);
  // a wheel joint the file makes fixed (the Pioneer 3-DX's, with "continuous" commented out):
  // Gazebo merges fixed joints away, so its plugin does not find the joint and the robot loads
  // without a drive; so it does here, with a warning
  for (const auto* side : {&left, &right}) {
    for (const auto& n : *side) {
      const int j = out.spec.joint_index(n);
      if (j >= 0 && out.spec.joints[static_cast<std::size_t>(j)].type == JointSpec::Type::fixed) {
        out.diagnostics.warn(index.at(plugin), "plugin '" + filename + "' is ignored: its wheel joint '" + n +
                                                   "' is fixed (Gazebo merges fixed joints, so its plugin does not find it either); "
                                                   "the robot has no drive");
        return;
      }
    }
  }
  // ROS 1's gazebo_ros_diff_drive turns the wrong way round, so many URDFs name the right wheel
  // its leftJoint to compensate: the sides are taken from where the wheels are
  if (configure_diff_drive(out.spec, left, right, diameter / 2, separation, index.at(plugin), true)) {
    out.diagnostics.warn(index.at(plugin), "plugin '" + filename +
                                               "' names the right-hand wheels as its left ones (a common workaround for the ROS 1 "
                                               "plugin's reversed turning): rescuesim takes each side from where its wheels are");
  }
  const double torque = child_number(plugin, {"wheelTorque", "max_wheel_torque", "torque"}, 0, index);
  if (torque > 0) {
    for (const auto* side : {&left, &right}) {
      for (const auto& n : *side) out.spec.joints[static_cast<std::size_t>(out.spec.joint_index(n))].max_effort = torque;
    }
  }
  out.drive_source = "plugin " + filename;
}

/// Noise stddev of a <noise> block (Gazebo's gaussian), 0 when there is none.
double noise_of(const XMLElement* e, const XmlIndex& index) {
  const XMLElement* n = e ? e->FirstChildElement("noise") : nullptr;
  return n ? child_number(n, {"stddev"}, 0, index) : 0;
}

void read_camera(const XMLElement* cam, SensorSpec& s, const XmlIndex& index) {
  s.camera.hfov = child_number(cam, {"horizontal_fov"}, s.camera.hfov, index);
  if (const XMLElement* img = cam->FirstChildElement("image")) {
    s.camera.width = child_count(img, "width", s.camera.width, 1, 8192, index, s.name);
    s.camera.height = child_count(img, "height", s.camera.height, 1, 8192, index, s.name);
  }
  if (const XMLElement* clip = cam->FirstChildElement("clip")) {
    s.camera.near_clip = child_number(clip, {"near"}, s.camera.near_clip, index);
    s.camera.far_clip = child_number(clip, {"far"}, s.camera.far_clip, index);
    s.camera.max_range = std::min(s.camera.max_range, s.camera.far_clip);
  }
  s.camera.noise.stddev = noise_of(cam, index);
  if (!(s.camera.hfov > 0 && s.camera.hfov < M_PI) || s.camera.width < 1 || s.camera.height < 1 || s.camera.width > 8192 ||
      s.camera.height > 8192) {
    throw Error(index.at(cam), "camera needs 0 < horizontal_fov < pi and an image of 1..8192 pixels a side");
  }
}

Pose3 pose_of(const XMLElement* e, const XmlIndex& index) {
  const XMLElement* p = e->FirstChildElement("pose");
  if (!p || !p->GetText()) return Pose3{};
  const auto v = numbers_of(p->GetText(), 6, index, p, "<pose>");
  return Pose3::from_rpy(Vec3(v[0], v[1], v[2]), v[3], v[4], v[5]);
}

}  // namespace

void read_sensor(const XMLElement* sensor, const std::string& link, const XmlIndex& index, UrdfRobot& out) {
  const std::string type = sensor->Attribute("type") ? sensor->Attribute("type") : "";
  const std::string name = sensor->Attribute("name") ? sensor->Attribute("name") : link + "_" + type;
  SensorSpec s;
  s.name = name;
  s.link = link;
  s.X_LS = pose_of(sensor, index);
  s.rate = child_number(sensor, {"update_rate"}, 10, index);
  if (!(s.rate > 0)) s.rate = 10;
  s.frame_id = link;
  const XMLElement* plugin = sensor->FirstChildElement("plugin");
  std::string topic = plugin ? child_text(plugin, {"topicName", "topic_name"}) : "";
  if (plugin) {
    const std::string frame = child_text(plugin, {"frameName", "frame_name"});
    if (!frame.empty()) s.frame_id = frame;
  }
  auto count = [&](SensorSpec::Type t) {
    int n = 0;
    for (const auto& x : out.spec.sensors) n += x.type == t;
    return n;
  };
  if (type == "ray" || type == "gpu_ray" || type == "lidar" || type == "gpu_lidar") {
    s.type = SensorSpec::Type::lidar;
    const XMLElement* ray = sensor->FirstChildElement("ray") ? sensor->FirstChildElement("ray") : sensor->FirstChildElement("lidar");
    if (const XMLElement* h = path(ray, {"scan", "horizontal"})) {
      s.lidar.samples = child_count(h, "samples", s.lidar.samples, 2, 100000, index, name);
      s.lidar.min_angle = child_number(h, {"min_angle"}, s.lidar.min_angle, index);
      s.lidar.max_angle = child_number(h, {"max_angle"}, s.lidar.max_angle, index);
    }
    if (const XMLElement* v = path(ray, {"scan", "vertical"})) {
      s.lidar.layers = child_count(v, "samples", 1, 1, 256, index, name);
      s.lidar.vertical_fov = child_number(v, {"max_angle"}, 0, index) - child_number(v, {"min_angle"}, 0, index);
    }
    if (const XMLElement* r = path(ray, {"range"})) {
      s.lidar.min_range = child_number(r, {"min"}, s.lidar.min_range, index);
      s.lidar.max_range = child_number(r, {"max"}, s.lidar.max_range, index);
    }
    s.lidar.noise.stddev = noise_of(ray, index);
    if (s.lidar.samples < 2 || s.lidar.samples > 100000 || !(s.lidar.max_angle > s.lidar.min_angle) ||
        !(s.lidar.max_range > s.lidar.min_range) || s.lidar.layers < 1 || s.lidar.layers > 256) {
      throw Error(index.at(sensor), "ray sensor '" + name + "' needs 2..100000 samples, min_angle < max_angle and min < max range");
    }
    s.topic = !topic.empty() ? topic : count(SensorSpec::Type::lidar) == 0 ? "scan" : name + "/scan";
  } else if (type == "camera" || type == "depth" || type == "rgbd_camera" || type == "depth_camera") {
    const bool depth = type != "camera";
    s.type = depth ? SensorSpec::Type::depth_camera : SensorSpec::Type::color_camera;
    if (const XMLElement* cam = sensor->FirstChildElement("camera")) read_camera(cam, s, index);
    s.topic = !topic.empty() ? topic : name + (depth ? "/depth/image_raw" : "/image_raw");
  } else if (type == "multicamera") {
    int k = 0;
    for (const XMLElement* cam = sensor->FirstChildElement("camera"); cam; cam = cam->NextSiblingElement("camera"), ++k) {
      SensorSpec c = s;
      c.type = SensorSpec::Type::color_camera;
      const std::string cname = cam->Attribute("name") ? cam->Attribute("name") : std::to_string(k);
      c.name = name + "_" + cname;
      c.X_LS = s.X_LS * pose_of(cam, index);
      c.frame_id = link + "_" + cname;
      read_camera(cam, c, index);
      c.topic = name + "/" + cname + "/image_raw";
      out.spec.sensors.push_back(c);
    }
    return;
  } else if (type == "imu") {
    s.type = SensorSpec::Type::imu;
    if (const XMLElement* imu = sensor->FirstChildElement("imu")) {
      if (const XMLElement* g = path(imu, {"angular_velocity", "x"})) s.imu.gyro.stddev = noise_of(g, index);
      if (const XMLElement* a = path(imu, {"linear_acceleration", "x"})) s.imu.accel.stddev = noise_of(a, index);
      if (imu->FirstChildElement("noise")) {
        const XMLElement* n = imu->FirstChildElement("noise");
        if (const XMLElement* r = n->FirstChildElement("rate")) s.imu.gyro.stddev = child_number(r, {"stddev"}, 0, index);
        if (const XMLElement* a = n->FirstChildElement("accel")) s.imu.accel.stddev = child_number(a, {"stddev"}, 0, index);
      }
    }
    s.topic = !topic.empty() ? topic : count(SensorSpec::Type::imu) == 0 ? "imu" : name;
  } else {
    out.diagnostics.warn(index.at(sensor), "sensor '" + name + "' of type '" + type +
                                               "' is ignored (rescuesim reads ray, gpu_ray, camera, depth, multicamera and imu sensors)");
    return;
  }
  if (plugin) {
    const std::string f = plugin->Attribute("filename") ? plugin->Attribute("filename") : "";
    if (!kCovered.count(f)) out.diagnostics.warn(index.at(plugin), "sensor plugin '" + f + "' is ignored (the sensor itself is simulated)");
  }
  out.spec.sensors.push_back(s);
}

namespace {

/// The value of a Gazebo extension element as Gazebo's URDF conversion reads it (sdformat's
/// parser_urdf, GetKeyValueAsString): its `value` attribute when it has one (`<mu1 value="1"/>`,
/// common in older URDFs), its text otherwise (`<mu1>1</mu1>`).
double gazebo_number(const XMLElement* e, const XmlIndex& index) {
  const char* attribute = e->Attribute("value");
  const std::string text = attribute ? std::string(attribute) : trimmed(e->GetText() ? e->GetText() : "");
  return numbers_of(text.c_str(), 1, index, e, std::string("<") + e->Name() + ">")[0];
}

/// Gives a link's collision shapes a contact material of their own with friction `mu1` (Bullet's
/// is isotropic); a differing `mu2` becomes an anisotropic scale along the link's y axis
/// (Gazebo's second friction direction by default).
void set_link_friction(const std::string& link, double mu1, double mu2, UrdfRobot& out) {
  RobotSpec& spec = out.spec;
  MaterialSpec m;
  m.name = spec.model + "/" + link + "_contact";
  m.color = Vec3(0.5, 0.5, 0.5);
  m.friction = mu1;
  spec.materials.push_back(m);
  LinkSpec& ls = spec.links[static_cast<std::size_t>(spec.link_index(link))];
  for (LinkShape& sh : ls.shapes) {
    if (sh.collides) sh.material = m.name;
  }
  if (mu1 > 0 && mu2 != mu1) ls.friction_scale = Vec3(1.0, mu2 / mu1, 1.0);
}

void check_friction(double mu1, double mu2, const XMLElement* where, const std::string& link, const XmlIndex& index) {
  if (!(mu1 >= 0) || !(mu2 >= 0) || mu1 > 1e3 || mu2 > 1e3) {
    throw Error(index.at(where), "link '" + link + "': friction coefficients must be in [0, 1000], got " + std::to_string(mu1) +
                                     (mu2 != mu1 ? " and " + std::to_string(mu2) : std::string()));
  }
}

/// A link's contact friction from Gazebo's <mu1> and <mu2> (either form, gazebo_number); true
/// when the block gives one.
bool read_friction(const XMLElement* g, const std::string& link, const XmlIndex& index, UrdfRobot& out) {
  const XMLElement* e1 = g->FirstChildElement("mu1");
  const XMLElement* e2 = g->FirstChildElement("mu2");
  if (!e1 && !e2) return false;
  const double mu1 = gazebo_number(e1 ? e1 : e2, index);
  const double mu2 = e2 ? gazebo_number(e2, index) : mu1;
  check_friction(mu1, mu2, g, link, index);
  set_link_friction(link, mu1, mu2, out);
  return true;
}

/// The children of a <gazebo reference="link"> block that rescuesim reads; every other one gets
/// a note saying it is ignored (Gazebo-classic's kp, kd, minDepth, maxVel, selfCollide,
/// material, ...: contact stiffness, solver and visual settings rescuesim's physics sets itself).
const std::set<std::string> kReadInLinkBlock{"mu1", "mu2", "sensor", "plugin"};

/// PyBullet's <contact> block in a <link> (lateral_friction, rolling_friction, stiffness, ...):
/// lateral_friction is the link's friction, as PyBullet reads it, unless a Gazebo block gave
/// <mu1>; the rest is ignored, each with a note.
void read_pybullet_contact(const XMLElement* link, bool gazebo_friction, const XmlIndex& index, UrdfRobot& out) {
  const XMLElement* contact = link->FirstChildElement("contact");
  if (!contact) return;
  const std::string name = link->Attribute("name") ? link->Attribute("name") : "";
  for (const XMLElement* c = contact->FirstChildElement(); c; c = c->NextSiblingElement()) {
    const std::string what = c->Name();
    if (what == "lateral_friction") {
      if (gazebo_friction) {
        out.diagnostics.warn(index.at(c),
                             "link '" + name + "': PyBullet's <lateral_friction> is ignored, the <gazebo> block's <mu1> is used");
        continue;
      }
      const double mu = gazebo_number(c, index);
      check_friction(mu, mu, c, name, index);
      set_link_friction(name, mu, mu, out);
    } else {
      out.diagnostics.warn(index.at(c), "link '" + name + "': PyBullet's <contact> <" + what + "> is ignored (rescuesim sets contact " +
                                            "stiffness, damping and rolling friction itself)");
    }
  }
}

}  // namespace

void read_gazebo(const XMLElement* robot, const XmlIndex& index, UrdfRobot& out) {
  std::set<std::string> with_friction;  // links a <gazebo> block gave <mu1>/<mu2>
  for (const XMLElement* g = robot->FirstChildElement("gazebo"); g; g = g->NextSiblingElement("gazebo")) {
    const char* reference = g->Attribute("reference");
    if (reference && !index.links.count(reference)) {
      if (index.joints.count(reference)) continue;  // joint settings (e.g. implicitSpringDamper): nothing to honour
      // Gazebo's URDF conversion applies nothing for it either (xacro leftovers of a removed link)
      out.diagnostics.warn(index.at(g), "<gazebo reference=\"" + std::string(reference) + "\"> names no link of the robot: ignored");
      continue;
    }
    if (reference && index.links.count(reference)) {
      if (read_friction(g, reference, index, out)) with_friction.insert(reference);
      for (const XMLElement* c = g->FirstChildElement(); c; c = c->NextSiblingElement()) {
        if (kReadInLinkBlock.count(c->Name())) continue;
        out.diagnostics.warn(index.at(c), "link '" + std::string(reference) + "': Gazebo's <" + c->Name() + "> is ignored");
      }
    }
    for (const XMLElement* s = g->FirstChildElement("sensor"); s; s = s->NextSiblingElement("sensor")) {
      read_sensor(s, reference ? reference : index.link_order.front(), index, out);
    }
    for (const XMLElement* p = g->FirstChildElement("plugin"); p; p = p->NextSiblingElement("plugin")) {
      const std::string filename = p->Attribute("filename") ? p->Attribute("filename") : "";
      if (kDiffDrive.count(filename)) {
        read_drive_plugin(p, filename, index, out);
      } else if (!kCovered.count(filename)) {
        out.diagnostics.warn(index.at(p), "plugin '" + filename + "' is ignored: rescuesim does not know what it does");
      }
    }
  }
  for (const auto& name : index.link_order) read_pybullet_contact(index.links.at(name), with_friction.count(name) > 0, index, out);
}

}  // namespace rescuesim::urdf_detail
