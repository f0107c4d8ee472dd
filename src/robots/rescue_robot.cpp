#include "robots/rescue_robot.h"

#include <cmath>

namespace rescuesim {

namespace {

constexpr double deg = M_PI / 180.0;
/// Sideways friction of a wheel relative to its rolling friction.
constexpr double kWheelSideFriction = 0.25;

Pose3 at(double x, double y, double z) { return {Vec3(x, y, z), Quat::Identity()}; }
Pose3 at_rpy(double x, double y, double z, double roll, double pitch, double yaw) {
  return Pose3::from_rpy(Vec3(x, y, z), roll, pitch, yaw);
}

/// Principal moments of a solid box of mass m and full extents s.
Vec3 box_inertia(double m, const Vec3& s) {
  return m / 12.0 * Vec3(s.y() * s.y() + s.z() * s.z(), s.x() * s.x() + s.z() * s.z(), s.x() * s.x() + s.y() * s.y());
}

LinkShape shape(Geometry g, Pose3 X_LG, const char* material, bool collides = true) {
  return {std::move(g), X_LG, material, collides};
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

}  // namespace

RobotSpec rescue_robot() {
  RobotSpec r;
  r.model = "rescue_robot";

  // chassis: base_link at the centre of the body box, 0.15 m above the ground at rest
  const Vec3 body(0.60, 0.40, 0.18);
  LinkSpec base{"base_link", 17.0, box_inertia(17.0, body), Vec3::Zero(), {}};
  base.shapes.push_back(shape(Geometry::box(body), {}, "robot_body"));
  base.shapes.push_back(shape(Geometry::box({0.06, 0.10, 0.06}), at(0.26, 0, 0.12), "robot_sensor"));  // laser housing
  r.links.push_back(base);

  // four wheels: spheres touch the ground (one clean contact each), cylinders are what you see
  const double wheel_r = 0.11, wheel_w = 0.07, wheel_x = 0.18, wheel_y = 0.245, wheel_z = -0.04;
  const char* wheel_names[4] = {"front_left", "front_right", "rear_left", "rear_right"};
  const double wx[4] = {wheel_x, wheel_x, -wheel_x, -wheel_x};
  const double wy[4] = {wheel_y, -wheel_y, wheel_y, -wheel_y};
  for (int i = 0; i < 4; ++i) {
    const std::string link = std::string(wheel_names[i]) + "_wheel";
    LinkSpec w{link, 1.2, Vec3(0.0037, 0.0073, 0.0037), Vec3::Zero(), {}, Vec3(1.0, kWheelSideFriction, 1.0)};
    w.shapes.push_back(shape(Geometry::sphere(wheel_r), {}, "robot_wheel"));
    w.shapes.push_back(shape(Geometry::cylinder(wheel_r, wheel_w), at_rpy(0, 0, 0, M_PI / 2, 0, 0), "robot_wheel", false));
    r.links.push_back(w);
    JointSpec j;
    j.name = link + "_joint";
    j.type = JointSpec::Type::continuous;
    j.parent = "base_link";
    j.child = link;
    j.X_PJ = at(wx[i], wy[i], wheel_z);
    j.axis = Vec3::UnitY();
    j.max_effort = 25.0;
    j.max_velocity = 20.0;
    j.control = JointSpec::Control::velocity;
    r.joints.push_back(j);
    (wy[i] > 0 ? r.drive.left_wheels : r.drive.right_wheels).push_back(j.name);
  }
  r.drive.wheel_radius = wheel_r;
  r.drive.track_width = 2 * wheel_y;
  r.drive.track_multiplier = 1.25;

  // the 4-DOF sensor head: mast yaw, shoulder pitch, elbow pitch, head tilt
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
      {"mast_yaw", "mast", at(-0.18, 0, 0.09), Vec3::UnitZ(), -170 * deg, 170 * deg, 20, 0, 1.0, Geometry::cylinder(0.035, 0.25),
       at(0, 0, 0.125)},
      {"shoulder_pitch", "upper_arm", at(0, 0, 0.25), Vec3::UnitY(), -90 * deg, 90 * deg, 40, 0, 0.7,
       Geometry::box({0.05, 0.05, 0.30}), at(0, 0, 0.15)},
      {"elbow_pitch", "forearm", at(0, 0, 0.30), Vec3::UnitY(), -150 * deg, 150 * deg, 25, 90 * deg, 0.5,
       Geometry::box({0.04, 0.04, 0.25}), at(0, 0, 0.125)},
      {"head_tilt", "head", at(0, 0, 0.25), Vec3::UnitY(), -120 * deg, 60 * deg, 10, -70 * deg, 0.8,
       Geometry::box({0.10, 0.22, 0.10}), at(0.05, 0, 0)},
  };
  std::string parent = "base_link";
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

  // sensors: a 270° laser at the front, four corner sonars, IMU, odometry, ground truth,
  // joint states and a bumper
  SensorSpec laser = sensor("laser", SensorSpec::Type::lidar, "base_link", at(0.26, 0, 0.16), 10, "scan", "laser");
  laser.lidar = LidarSpec{};
  r.sensors.push_back(laser);
  const struct {
    const char* name;
    double x, y, yaw;
  } sonars[4] = {{"front_left", 0.30, 0.15, 25 * deg},
                 {"front_right", 0.30, -0.15, -25 * deg},
                 {"rear_left", -0.30, 0.15, 155 * deg},
                 {"rear_right", -0.30, -0.15, -155 * deg}};
  for (const auto& s : sonars) {
    SensorSpec so = sensor(std::string("sonar_") + s.name, SensorSpec::Type::sonar, "base_link", at_rpy(s.x, s.y, 0.0, 0, 0, s.yaw),
                           10, std::string("sonar/") + s.name, std::string("sonar_") + s.name);
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
  return r;
}

std::map<std::string, RobotSpec> builtin_models() { return {{"rescue_robot", rescue_robot()}}; }

}  // namespace rescuesim
