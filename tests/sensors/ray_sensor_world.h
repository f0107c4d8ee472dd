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

}  // namespace rescuesim::testing
