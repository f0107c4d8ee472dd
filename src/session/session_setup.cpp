// Session::attach_controllers: which robot gets which built-in controller, and how it is set up
// for the world it runs in (team/builtin_controllers.h runs them).

#include "autonomy/explorer.h"
#include "session/explorer_settings.h"
#include "session/session.h"
#include "world/robot_lumping.h"

namespace rescuesim {

namespace {
constexpr double kWallFollowerMapPeriod = 0.5;  // s between scans a wall follower outside a mission maps

/// The map covers the whole floor (and a margin) wherever the robot starts: the square the
/// mapper allocates around the start by default (auto_size, 40 m) would leave the far side of a
/// larger world unmapped, and a robot in a corner of a 30 m maze could map only half of it.
/// Worlds that square covers keep it.
void fit_map_to_floor(autonomy::ExplorerConfig& ec, const Box2& floor, const Pose2& X_WO) {
  if (floor.empty()) return;
  const Pose2 X_OW = X_WO.inverse();
  constexpr double kMargin = 2.0;  // m
  Box2 box_O;
  for (const Vec2& corner : {floor.min, floor.max, Vec2(floor.min.x(), floor.max.y()), Vec2(floor.max.x(), floor.min.y())}) {
    box_O.extend(X_OW.transform(corner));
  }
  box_O.min -= Vec2(kMargin, kMargin);
  box_O.max += Vec2(kMargin, kMargin);
  // the default square is centred on the laser at the start, near the odom frame's origin
  const double reach = ec.map.auto_size / 2 - 1.0;
  if (box_O.min.minCoeff() < -reach || box_O.max.maxCoeff() > reach) {
    ec.map.size = box_O.max - box_O.min;
    ec.map.origin_O = box_O.min;
  }
}
}  // namespace

void Session::attach_controllers(const ModelMap& models) {
  const auto configs = robot_configs(scenario_, spec_, models);
  for (std::size_t r = 0; r < sim_->world().robots.size() && r < configs.size(); ++r) {
    if (configs[r].controller == "none") continue;
    const RobotInstance& robot = sim_->world().robots[r];
    const SensorSpec* laser = nullptr;
    const SensorSpec* odom = nullptr;
    const SensorSpec* joints = nullptr;
    for (const auto& s : robot.spec.sensors) {
      if (s.enabled && s.type == SensorSpec::Type::lidar && s.lidar.layers == 1 && !laser) laser = &s;
      if (s.enabled && s.type == SensorSpec::Type::odometry && !odom) odom = &s;
      if (s.enabled && s.type == SensorSpec::Type::joint_states && !joints) joints = &s;
    }
    const std::string& kind = configs[r].controller;
    const SourceRef where{scenario_.source_file, 0, "robots[" + std::to_string(r) + "].controller"};
    if (!laser || !odom) throw Error(where, "the " + kind + " needs an enabled planar laser and odometry (a drive)");
    // the laser must sit on the root link, or on links fixed to it (the root's rigid body)
    const int laser_link = robot.spec.link_index(laser->link);
    const LumpedRobot lumped = lump_fixed_joints(robot.spec);
    if (lumped.body_of_link[static_cast<std::size_t>(laser_link)] != 0) {
      throw Error(where, "the " + kind + " needs its laser fixed to the robot's body; link '" + laser->link + "' moves on a joint");
    }
    const Pose3 X_BS = laser_link == 0 ? laser->X_LS : lumped.X_BL[static_cast<std::size_t>(laser_link)] * laser->X_LS;
    autonomy::ExplorerConfig config = builtin_explorer_config(kind, robot.spec);
    // other robots about: give their masts (all the laser sees of them) a berth as wide as a
    // rescue robot's reach from its mast (0.48 m to the front bumper)
    if (sim_->world().robots.size() > 1) config.post_radius = 0.5;
    // scan matching keeps the map true for plans and reports; a robot that does neither (a
    // wall follower outside a mission) steers by the laser alone: it skips matching (a fifth
    // of the work of 100 such robots) and maps at 2 Hz, not at its laser's 10 Hz (mapping
    // every scan was a quarter of it; docs/design-notes/performance-history.md)
    if (!config.frontier_trips && !mission_) {
      config.scan_matching = false;
      config.map_period = kWallFollowerMapPeriod;
    }
    const Pose2 X_WO = robot.X_W_start.to_pose2();
    fit_map_to_floor(config, sim_->world().floor, X_WO);
    // the victim camera's pan: where it stands, and the swing the explorer asks for (a head
    // joint is commanded with the whole head, the others held at their starting positions)
    const RobotIndex ri = RobotIndex::at(r);
    std::vector<std::string> topics{sim_->topic_name(ri, odom->topic)};
    BuiltinControllers::Pan pan;
    if (!config.look.yaw_joint.empty()) {
      pan.joint.name = {config.look.yaw_joint};
      pan.joint.position = {0.0};
      const auto& hj = robot.spec.head_joints;
      for (std::size_t k = 0; k < hj.size(); ++k) {
        pan.head.push_back(robot.spec.joints[static_cast<std::size_t>(robot.spec.joint_index(hj[k]))].initial);
        if (hj[k] == config.look.yaw_joint) pan.in_head = static_cast<int>(k);
      }
      if (joints) topics.push_back(sim_->topic_name(ri, joints->topic));
    }
    topics.push_back(sim_->topic_name(ri, laser->topic));
    controllers_->attach(*sim_, ri, std::make_unique<autonomy::Explorer>(X_BS.to_pose2(), config), X_WO, std::move(pan), topics);
  }
}

}  // namespace rescuesim
