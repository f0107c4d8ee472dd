#include "session/explorer_settings.h"

#include <algorithm>

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
  return ec;
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
