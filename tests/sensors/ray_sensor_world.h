#pragma once
// Small worlds for the ray-sensor tests (lidar, sonar): a floor, a wall whose near face is a
// plane x = d, and box robots carrying one sensor in their base link.

#include <map>
#include <string>
#include <vector>

#include "world/state.h"
#include "world/world.h"

namespace rescuesim::testing {

/// A 0.4 × 0.4 × 0.3 m box centred on base_link, standing with its bottom 2 mm above the floor
/// (so base_link is 0.152 m up), carrying `sensor` (if any, its link is base_link).
inline RobotSpec box_robot(const std::vector<SensorSpec>& sensors = {}) {
  RobotSpec r;
  r.model = "box_bot";
  LinkSpec base;
  base.name = "base_link";
  base.shapes.push_back({Geometry::box({0.4, 0.4, 0.3}), Pose3{}, "robot_body", true});
  r.links.push_back(base);
  r.sensors = sensors;
  return r;
}

/// Height of base_link above the floor for box_robot (m): half the box plus 2 mm.
inline constexpr double kBaseHeight = 0.152;

/// An empty 10 m × 10 m floor around the origin.
inline WorldSpec empty_spec() {
  WorldSpec s;
  s.name = "sensor_test";
  s.materials = default_materials();
  s.floor_min = {-5, -5};
  s.floor_max = {5, 5};
  return s;
}

/// A 1 m high, 40 m long, 0.1 m thick wall whose west face is the plane x = d.
inline WallSpec wall_facing_west(double d) { return WallSpec{{d + 0.05, -20}, {d + 0.05, 20}, 0.1, 1.0, "wall", {}}; }

/// Compiles with the given robot model available as "box_bot".
inline World compile_with(const WorldSpec& spec, const RobotSpec& model) { return compile_world(spec, {{"box_bot", model}}); }

/// The state at the start: rubble where the world put it, robots at their start poses.
inline State initial_state(const World& w) {
  State s;
  for (const auto& d : w.dynamics) s.dynamics.push_back({d.X_WO});
  for (const auto& r : w.robots) {
    RobotState rs;
    for (const Pose3& X_BL : link_poses(r.spec, initial_positions(r.spec))) rs.X_WL.push_back(r.X_W_start * X_BL);
    rs.base.X_WB = rs.X_WL.front();
    s.robots.push_back(rs);
  }
  return s;
}

}  // namespace rescuesim::testing
