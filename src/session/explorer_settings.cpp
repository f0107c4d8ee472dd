#include "session/explorer_settings.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace rescuesim {

autonomy::ExplorerConfig builtin_explorer_config(const std::string& controller) {
  if (controller != "explorer" && controller != "wall_follower") {
    throw Error("builtin_explorer_config: controller '" + controller + "' is neither explorer nor wall_follower");
  }
  autonomy::ExplorerConfig ec;
  // the robot as a disc around base_link: half the diagonal of its footprint with wheels
  ec.robot_radius = 0.41;
  if (controller == "wall_follower") ec.frontier_trips = false;  // never plans: pure wall following
  // frontier to frontier, wall following only while nothing is left to explore; near the
  // drive's 1 m/s (default scenario, seeds 1-20, every victim found: 12 of 20 runs at 0.7 m/s,
  // 17 at 0.9, 16 at 1.0; docs/missions.md)
  ec.frontier_first = true;
  ec.wall.max_linear = 0.9;
  ec.path.max_linear = 0.9;
  return ec;
}

autonomy::ExplorerLookConfig victim_camera_look(const RobotSpec& robot, bool swing) {
  autonomy::ExplorerLookConfig look;
  // the camera victims are found with: the last thermal camera, as the victim detectors take
  const SensorSpec* cam = nullptr;
  for (const auto& s : robot.sensors) {
    if (s.type == SensorSpec::Type::thermal_camera) cam = &s;
  }
  const int link = cam ? robot.link_index(cam->link) : -1;
  if (link < 0) return look;
  look.enabled = true;
  // a little inside the camera's reach: a victim counts when its parts are well in the frame
  look.fan.hfov = 0.85 * cam->camera.hfov;
  look.fan.range = 0.8 * cam->camera.max_range;
  // the camera's heading in base_link at the start, and the nearest joint above it that turns
  // it about the vertical (a pan joint, or a mast's yaw)
  const std::vector<double> q0 = initial_positions(robot);
  const std::vector<Pose3> X_BL = link_poses(robot, q0);
  const Pose3 X_BC = X_BL[static_cast<std::size_t>(link)] * cam->X_LS;
  const double yaw0 = X_BC.to_pose2().yaw;
  look.fixed_yaw = yaw0;
  if (!swing) return look;
  std::string child = robot.links[static_cast<std::size_t>(link)].name;
  for (std::size_t hop = 0; hop < robot.joints.size(); ++hop) {
    const auto j = std::find_if(robot.joints.begin(), robot.joints.end(), [&](const JointSpec& js) { return js.child == child; });
    if (j == robot.joints.end()) break;
    const bool turns = j->type == JointSpec::Type::revolute || j->type == JointSpec::Type::continuous;
    const bool commandable = j->control == JointSpec::Control::position && j->mimic.empty();
    if (turns && commandable) {
      // the axis in base_link at the start: vertical within 10 degrees
      const int parent = robot.link_index(j->parent);
      const Vec3 axis_B = (X_BL[static_cast<std::size_t>(parent)] * j->X_PJ).q * j->axis.normalized();
      if (std::abs(axis_B.z()) > std::cos(10 * M_PI / 180)) {
        look.yaw_joint = j->name;
        look.yaw_sign = axis_B.z() > 0 ? 1.0 : -1.0;
        look.fixed_yaw = yaw0 - look.yaw_sign * q0[static_cast<std::size_t>(j - robot.joints.begin())];
        // a swing within the joint's limits
        const double centre = 0.5 * (j->lower + j->upper);
        if (j->type == JointSpec::Type::revolute && std::abs(centre) < 1e-9) {
          look.sweep_amplitude = std::min(look.sweep_amplitude, 0.9 * j->upper);
        } else if (j->type == JointSpec::Type::revolute) {
          look.sweep_amplitude = 0;  // limits not around ahead: leave the camera where it is
        }
        break;
      }
    }
    child = j->parent;
  }
  return look;
}

double footprint_radius(const RobotSpec& robot) {
  const auto X_BL = link_poses(robot, initial_positions(robot));
  double r = 0;
  for (std::size_t l = 0; l < robot.links.size(); ++l) {
    for (const auto& sh : robot.links[l].shapes) {
      if (!sh.collides) continue;
      for (const Vec3& v : mesh_of(sh.geometry, 16).vertices) r = std::max(r, (X_BL[l] * (sh.X_LG * v)).head<2>().norm());
    }
  }
  return r;
}

autonomy::ExplorerConfig builtin_explorer_config(const std::string& controller, const RobotSpec& robot) {
  autonomy::ExplorerConfig ec = builtin_explorer_config(controller);
  if (ec.frontier_trips) ec.look = victim_camera_look(robot);
  if (robot.model == "rescue_robot") return ec;
  // a disc around the footprint with a little margin; wall distances keep the built-in's margins
  const double builtin = ec.robot_radius;
  ec.robot_radius = footprint_radius(robot) + 0.03;
  const double shrink = ec.robot_radius - builtin;
  ec.wall.target_distance = std::max(ec.robot_radius + 0.08, ec.wall.target_distance + shrink);
  ec.wall.slow_distance = std::max(0.3, ec.wall.slow_distance + shrink);
  ec.wall.stop_distance = std::max(0.08, ec.wall.stop_distance + 0.5 * shrink);
  ec.wall.wall_lost_distance = std::max(0.6, ec.wall.wall_lost_distance + shrink);
  ec.planner.cost.comfort_distance = std::max(ec.robot_radius + 0.15, ec.planner.cost.comfort_distance + shrink);
  ec.path.lookahead = std::max(0.3, ec.path.lookahead + shrink);
  ec.path.goal_tolerance = std::max(0.1, ec.path.goal_tolerance + 0.5 * shrink);
  ec.safety_slow_distance = std::max(0.3, ec.safety_slow_distance + shrink);
  // speeds within the drive's limits
  ec.wall.max_linear = std::min(ec.wall.max_linear, robot.drive.max_linear);
  ec.wall.max_angular = std::min(ec.wall.max_angular, robot.drive.max_angular);
  ec.path.max_linear = std::min(ec.path.max_linear, robot.drive.max_linear);
  ec.path.max_angular = std::min(ec.path.max_angular, robot.drive.max_angular);
  ec.backup_speed = std::min(ec.backup_speed, 0.5 * robot.drive.max_linear);
  return ec;
}

}  // namespace rescuesim
