#pragma once
// Test support: a world with the rescue robot stepped by Physics and the drive controllers,
// without the rest of the simulation, for hand-checkable motion tests.

#include <memory>

#include "physics/physics.h"
#include "robots/drive_controller.h"
#include "robots/rescue_robot.h"
#include "world/world.h"

namespace rescuesim::testing {

/// A square room of the given size (m) with 1 m high walls and the robot in the middle
/// facing east (+x), plus whatever the caller adds to the spec first.
inline WorldSpec room_spec(double size = 20.0, Pose2 start = {0, 0, 0}) {
  WorldSpec w;
  w.floor_min = {-size / 2, -size / 2};
  w.floor_max = {size / 2, size / 2};
  w.materials = default_materials();
  const double h = size / 2;
  w.walls = {{{-h, -h}, {h, -h}, 0.1, 1, "wall", {}},
             {{h, -h}, {h, h}, 0.1, 1, "wall", {}},
             {{h, h}, {-h, h}, 0.1, 1, "wall", {}},
             {{-h, h}, {-h, -h}, 0.1, 1, "wall", {}}};
  RobotPlacement r;
  r.start = start;
  w.robots.push_back(r);
  return w;
}

/// The mission bridge tests' world: a 20 m room_spec with robots "robot" at (0, -2) and
/// "robot2" at (0, 2), 4 m apart, and victim "v1" at (5, 0).
inline WorldSpec two_robots_and_a_victim() {
  WorldSpec spec = room_spec(20.0, {0, -2, 0});
  RobotPlacement second;
  second.name = "robot2";
  second.start = {0, 2, 0};
  spec.robots.push_back(second);
  VictimSpec v;
  v.name = "v1";
  v.pose = {5, 0, 0};
  spec.victims.push_back(v);
  return spec;
}

struct Rig {
  World world;
  std::unique_ptr<Physics> physics;
  State state;

  explicit Rig(const WorldSpec& spec, PhysicsOptions options = {}) : world(compile_world(spec, builtin_models())) {
    physics = std::make_unique<Physics>(world, options);
    physics->init_state(state);
  }
  double dt() const { return physics->dt(); }
  RobotState& robot() { return state.robots.at(0); }
  const RobotSpec& spec() const { return world.robots.at(0).spec; }

  /// Holds cmd_vel (v, w) for `seconds`, re-sent every step so it never times out.
  void drive(double v, double w, double seconds) {
    const long n = std::lround(seconds / dt());
    for (long i = 0; i < n; ++i) {
      robot().cmd_linear = Vec3(v, 0, 0);
      robot().cmd_angular = Vec3(0, 0, w);
      robot().cmd_time = state.time;
      step();
    }
  }
  /// One step: controllers, physics, clock.
  void step() {
    for (std::size_t r = 0; r < state.robots.size(); ++r) {
      update_drive(world.robots[r].spec, state.robots[r], state.time, dt());
      update_head(world.robots[r].spec, state.robots[r]);
    }
    physics->step(state);
    state.time += SimTime::from_seconds(dt());
    ++state.step;
  }
  void run(double seconds) {
    const long n = std::lround(seconds / dt());
    for (long i = 0; i < n; ++i) step();
  }
};

}  // namespace rescuesim::testing
