#pragma once
/// Parts the built-in robot models share: the 4-DOF sensor head with its cameras, the body's
/// sensors (laser, sonars, IMU, odometry, ground truth, joint states, bumper) and small helpers.
/// Internal to src/robots.

#include <cmath>
#include <string>
#include <vector>

#include "world/robot_spec.h"

namespace rescuesim::robot_parts {

inline constexpr double kDeg = M_PI / 180.0;  ///< one degree in radians

Pose3 at(double x, double y, double z);
Pose3 at_rpy(double x, double y, double z, double roll, double pitch, double yaw);
/// Principal moments of a solid box of mass m and full extents s.
Vec3 box_inertia(double m, const Vec3& s);
LinkShape shape(Geometry g, Pose3 X_LG, const char* material, bool collides = true);
SensorSpec sensor(const std::string& name, SensorSpec::Type type, const std::string& link, Pose3 X_LS, double rate,
                  const std::string& topic, const std::string& frame);

/// The 4-DOF sensor head (mast yaw, shoulder pitch, elbow pitch, head tilt; worm-geared,
/// self-locking joints driven by /head/command) on `parent` at `X_mount` (the mast's foot).
void add_sensor_head(RobotSpec& r, const std::string& parent, const Pose3& X_mount);

/// A sonar's mount on the chassis.
struct SonarMount {
  const char* name;
  double x, y, yaw;
};

/// The chassis sensors on base_link (a 270° laser at `X_laser`, a sonar at each mount, IMU,
/// odometry, ground truth, joint states and a bumper), then the head's colour, depth and
/// thermal cameras.
void add_sensors(RobotSpec& r, const Pose3& X_laser, const std::vector<SonarMount>& sonars, double sonar_z);

}  // namespace rescuesim::robot_parts
