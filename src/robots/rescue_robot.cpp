#include "robots/rescue_robot.h"

#include <cmath>

#include "robots/robot_parts.h"
#include "robots/tracked_robot.h"

namespace rescuesim {

namespace {

using namespace robot_parts;
constexpr double deg = kDeg;
/// Sideways friction of a wheel relative to its rolling friction.
constexpr double kWheelSideFriction = 0.25;

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

  // the 4-DOF sensor head at the back of the chassis; a 270° laser at the front, four sonars
  // at the corners, IMU, odometry, ground truth, joint states, a bumper and the head's cameras
  add_sensor_head(r, "base_link", at(-0.18, 0, 0.09));
  add_sensors(r, at(0.26, 0, 0.16),
              {{"front_left", 0.30, 0.15, 25 * deg},
               {"front_right", 0.30, -0.15, -25 * deg},
               {"rear_left", -0.30, 0.15, 155 * deg},
               {"rear_right", -0.30, -0.15, -155 * deg}},
              0.0);
  return r;
}

std::map<std::string, RobotSpec> builtin_models() { return {{"rescue_robot", rescue_robot()}, {"tracked_robot", tracked_robot()}}; }

}  // namespace rescuesim
