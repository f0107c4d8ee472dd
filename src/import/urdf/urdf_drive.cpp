// A differential or skid-steer drive on a URDF robot's wheel joints.
#include <cmath>

#include "import/urdf/urdf_import.h"

namespace rescuesim {

namespace {

std::string num(double v) { return std::to_string(v); }

/// Radius of a wheel link: its largest collision shape's extent around the joint axis.
double wheel_radius_of(const RobotSpec& robot, const JointSpec& joint) {
  const int l = robot.link_index(joint.child);
  double radius = 0;
  const Vec3 axis = joint.axis.normalized();
  for (const LinkShape& sh : robot.links[static_cast<std::size_t>(l)].shapes) {
    if (!sh.collides) continue;
    for (const Vec3& v : mesh_of(sh.geometry, 32).vertices) {
      const Vec3 p = sh.X_LG * v;
      radius = std::max(radius, (p - p.dot(axis) * axis).norm());
    }
  }
  return radius;
}

}  // namespace

bool configure_diff_drive(RobotSpec& robot, const std::vector<std::string>& left, const std::vector<std::string>& right,
                          double wheel_radius, double track_width, const SourceRef& where, bool sides_by_position) {
  if (left.empty() || right.empty()) throw Error(where, "a diff_drive needs at least one wheel joint on each side (left and right)");
  const std::vector<Pose3> X_BL = link_poses(robot, initial_positions(robot));
  DriveSpec& d = robot.drive;
  d.left_wheels = left;
  d.right_wheels = right;
  d.left_signs.clear();
  d.right_signs.clear();
  double radius_sum = 0, left_y = 0, right_y = 0;
  for (int side = 0; side < 2; ++side) {
    const auto& names = side == 0 ? left : right;
    for (const auto& name : names) {
      const int j = robot.joint_index(name);
      if (j < 0) {
        std::string known;
        for (const auto& js : robot.joints) known += (known.empty() ? "" : ", ") + js.name;
        throw Error(where, "wheel joint '" + name + "' is not a joint of the robot (joints: " + known + ")");
      }
      JointSpec& js = robot.joints[static_cast<std::size_t>(j)];
      if (js.type != JointSpec::Type::continuous && js.type != JointSpec::Type::revolute) {
        throw Error(where, "wheel joint '" + name + "' must be continuous (or revolute), not fixed or prismatic");
      }
      // the axis in the base frame must point sideways; its direction decides which way is forward
      const Pose3& X_BP = X_BL[static_cast<std::size_t>(robot.link_index(js.parent))];
      const Vec3 axis_B = (X_BP.q * js.X_PJ.q) * js.axis.normalized();
      if (std::abs(axis_B.y()) < 0.7) {
        throw Error(where, "wheel joint '" + name + "' turns about (" + num(axis_B.x()) + ", " + num(axis_B.y()) + ", " + num(axis_B.z()) +
                               ") in the base frame; a drive wheel's axis must point sideways (along y)");
      }
      (side == 0 ? d.left_signs : d.right_signs).push_back(axis_B.y() > 0 ? 1.0 : -1.0);
      js.control = JointSpec::Control::velocity;
      js.initial = 0;
      // wheels grip like the built-in robot's rubber (friction 1.0 rather than the body's 0.5)
      for (LinkShape& sh : robot.links[static_cast<std::size_t>(robot.link_index(js.child))].shapes) {
        if (sh.collides && sh.material == "robot_body") sh.material = "robot_wheel";
      }
      radius_sum += wheel_radius_of(robot, js);
      const double y = (X_BP * js.X_PJ).p.y();
      (side == 0 ? left_y : right_y) += y / static_cast<double>(names.size());
    }
  }
  if (wheel_radius > 0) {
    d.wheel_radius = wheel_radius;
  } else {
    d.wheel_radius = radius_sum / static_cast<double>(left.size() + right.size());
    if (!(d.wheel_radius > 1e-4))
      throw Error(where, "cannot tell the wheel radius (the wheel links have no collision shapes); give drive.wheel_radius");
  }
  d.track_width = track_width > 0 ? track_width : std::abs(left_y - right_y);
  if (!(d.track_width > 1e-4)) throw Error(where, "the left and right wheels are at the same place; give drive.wheel_separation");
  if (left_y < right_y) {
    if (sides_by_position) {
      configure_diff_drive(robot, right, left, wheel_radius, track_width, where, false);
      return true;
    }
    throw Error(where,
                "the 'left' wheels are to the right of the 'right' wheels (y " + num(left_y) + " < " + num(right_y) + " m); swap them");
  }
  // two wheels a side or more skid when turning: the effective track is wider (as the built-in robot's)
  d.track_multiplier = left.size() + right.size() > 2 ? 1.25 : 1.0;
  return false;
}

}  // namespace rescuesim
