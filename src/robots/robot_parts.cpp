#include "robots/robot_parts.h"

#include <cmath>

namespace rescuesim::robot_parts {

Pose3 at(double x, double y, double z) { return {Vec3(x, y, z), Quat::Identity()}; }
Pose3 at_rpy(double x, double y, double z, double roll, double pitch, double yaw) {
  return Pose3::from_rpy(Vec3(x, y, z), roll, pitch, yaw);
}

Vec3 box_inertia(double m, const Vec3& s) {
  return m / 12.0 * Vec3(s.y() * s.y() + s.z() * s.z(), s.x() * s.x() + s.z() * s.z(), s.x() * s.x() + s.y() * s.y());
}

LinkShape shape(Geometry g, Pose3 X_LG, const char* material, bool collides) {
  LinkShape sh;
  sh.geometry = std::move(g);
  sh.X_LG = X_LG;
  sh.material = material;
  sh.collides = collides;
  return sh;
}

SensorSpec sensor(const std::string& name, SensorSpec::Type type, const std::string& link, Pose3 X_LS, double rate,
                  const std::string& topic, const std::string& frame) {
  SensorSpec s;
  s.name = name;
  s.type = type;
  s.link = link;
  s.X_LS = X_LS;
  s.rate = rate;
  s.topic = topic;
  s.frame_id = frame;
  return s;
}

void add_sensor_head(RobotSpec& r, const std::string& parent_link, const Pose3& X_mount) {
  constexpr double deg = kDeg;
  struct Segment {
    const char* joint;
    const char* link;
    Pose3 X_PJ;
    Vec3 axis;
    double lower, upper, effort, initial, mass;
    Geometry geometry;
    Pose3 X_LG;
  };
  const Segment arm[4] = {
      {"mast_yaw", "mast", X_mount, Vec3::UnitZ(), -170 * deg, 170 * deg, 20, 0, 1.0, Geometry::cylinder(0.035, 0.25),
       at(0, 0, 0.125)},
      {"shoulder_pitch", "upper_arm", at(0, 0, 0.25), Vec3::UnitY(), -90 * deg, 90 * deg, 40, 0, 0.7,
       Geometry::box({0.05, 0.05, 0.30}), at(0, 0, 0.15)},
      {"elbow_pitch", "forearm", at(0, 0, 0.30), Vec3::UnitY(), -150 * deg, 150 * deg, 25, 90 * deg, 0.5,
       Geometry::box({0.04, 0.04, 0.25}), at(0, 0, 0.125)},
      {"head_tilt", "head", at(0, 0, 0.25), Vec3::UnitY(), -120 * deg, 60 * deg, 10, -70 * deg, 0.8,
       Geometry::box({0.10, 0.22, 0.10}), at(0.05, 0, 0)},
  };
  std::string parent = parent_link;
  for (const auto& s : arm) {
    LinkSpec l{s.link, s.mass, box_inertia(s.mass, s.geometry.size), s.X_LG.p, {}};
    l.shapes.push_back(shape(s.geometry, s.X_LG, std::string(s.link) == "head" ? "robot_sensor" : "robot_body"));
    r.links.push_back(l);
    JointSpec j;
    j.name = s.joint;
    j.type = JointSpec::Type::revolute;
    j.parent = parent;
    j.child = s.link;
    j.X_PJ = s.X_PJ;
    j.axis = s.axis;
    j.lower = s.lower;
    j.upper = s.upper;
    j.max_effort = s.effort;
    j.max_velocity = 1.5;
    j.control = JointSpec::Control::position;
    j.kp = 8.0;
    j.initial = s.initial;
    j.self_locking = true;  // worm-geared, like the pan-tilt units of real response robots
    r.joints.push_back(j);
    r.head_joints.push_back(s.joint);
    parent = s.link;
  }
  // a lamp under the cameras, shining where they look (off until /lights turns it on)
  RobotLightSpec lamp;
  lamp.name = "head_lamp";
  lamp.link = "head";
  lamp.X_LF = at(0.101, 0, -0.035);
  r.lights.push_back(lamp);
}

void add_sensors(RobotSpec& r, const Pose3& X_laser, const std::vector<SonarMount>& sonars, double sonar_z) {
  constexpr double deg = kDeg;
  SensorSpec laser = sensor("laser", SensorSpec::Type::lidar, "base_link", X_laser, 10, "scan", "laser");
  laser.lidar = LidarSpec{};
  r.sensors.push_back(laser);
  for (const auto& s : sonars) {
    SensorSpec so = sensor(std::string("sonar_") + s.name, SensorSpec::Type::sonar, "base_link",
                           at_rpy(s.x, s.y, sonar_z, 0, 0, s.yaw), 10, std::string("sonar/") + s.name, std::string("sonar_") + s.name);
    r.sensors.push_back(so);
  }
  r.sensors.push_back(sensor("imu", SensorSpec::Type::imu, "base_link", at(0, 0, 0), 100, "imu/data", "imu_link"));
  r.sensors.push_back(sensor("odometry", SensorSpec::Type::odometry, "base_link", {}, 50, "odom", "odom"));
  r.sensors.push_back(sensor("ground_truth", SensorSpec::Type::ground_truth, "base_link", {}, 50, "ground_truth/pose", "map"));
  r.sensors.push_back(sensor("joint_states", SensorSpec::Type::joint_states, "base_link", {}, 20, "joint_states", ""));
  r.sensors.push_back(sensor("bumper", SensorSpec::Type::contact, "base_link", {}, 20, "bumper", "base_link"));

  // the head's cameras, looking along the head's x axis (rendered by src/render)
  SensorSpec color = sensor("color_camera", SensorSpec::Type::color_camera, "head", at(0.10, 0.06, 0.0), 10, "camera/color/image_raw",
                            "camera_color");
  color.camera.width = 640;
  color.camera.height = 480;
  color.camera.hfov = 70 * deg;
  r.sensors.push_back(color);
  SensorSpec depth = sensor("depth_camera", SensorSpec::Type::depth_camera, "head", at(0.10, -0.06, 0.0), 10, "camera/depth/image_raw",
                            "camera_depth");
  depth.camera.width = 320;
  depth.camera.height = 240;
  depth.camera.hfov = 58 * deg;
  depth.camera.min_range = 0.3;
  depth.camera.max_range = 8.0;
  depth.camera.depth_noise_quadratic = 0.001;
  r.sensors.push_back(depth);
  // a small radiometric thermal camera (160 x 120, 57 degrees, like a FLIR Lepton)
  SensorSpec thermal = sensor("thermal_camera", SensorSpec::Type::thermal_camera, "head", at(0.10, 0.0, 0.04), 10, "thermal/image_raw",
                              "thermal_camera");
  thermal.camera.width = 160;
  thermal.camera.height = 120;
  thermal.camera.hfov = 57 * deg;
  thermal.camera.min_range = 0.1;
  thermal.camera.max_range = 6.0;
  thermal.camera.noise.stddev = 0.05;  // NETD 50 mK
  r.sensors.push_back(thermal);
}

}  // namespace rescuesim::robot_parts
