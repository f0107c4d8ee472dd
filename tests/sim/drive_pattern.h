#pragma once
// Test support for tests/sim: the default scenario's simulation (without its built-in
// controller) and a fixed driving pattern that records every message it publishes.

#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>
#include <vector>

#include "import/scenario/scenario.h"
#include "msgs/digest.h"
#include "robots/rescue_robot.h"
#include "sim/simulation.h"

namespace rescuesim::testing {

/// Every message a run published, in order: (topic id, digest).
struct Recording {
  std::vector<std::pair<int, std::uint64_t>> messages;
  std::uint64_t hash = 0;  ///< state_hash at the end
};

/// The default scenario's world, without its built-in controller (commands come from drive()).
inline std::unique_ptr<Simulation> default_sim() {
  const ModelMap models = builtin_models();
  const Scenario sc = default_scenario(models);
  SimOptions o;
  o.seed = sc.seed;
  return std::make_unique<Simulation>(compile_scenario(sc, build_world(sc), models), o);
}

/// Drives a fixed pattern, a function of sim time only, from now until `until`: cmd_vel every
/// 0.1 s (forward, swerving), a new head pose every 0.5 s; records what is published.
inline Recording drive(Simulation& sim, SimTime until) {
  Recording rec;
  // what is published from now on (not the latched messages subscribe replays)
  bool live = false;
  const auto handle = sim.bus().subscribe("", [&](const Topic& t, const msg::Message& m) {
    if (live) rec.messages.emplace_back(static_cast<int>(t.id), msg::digest(m));
  });
  live = true;
  while (sim.time() < until && !sim.in_trouble()) {
    const std::int64_t k = sim.time().ns / 100'000'000;  // tenths of a second
    msg::Twist t;
    t.linear.x() = 0.6;
    t.angular.z() = k % 30 < 15 ? 0.7 : -0.7;
    sim.command_velocity(RobotIndex(0), t);
    if (k % 5 == 0 && !sim.world().robots[0].spec.head_joints.empty()) {
      sim.command_head(RobotIndex(0), {0.4 * std::sin(static_cast<double>(k)), 0.2, 1.4, -1.0});
    }
    sim.step_until(std::min(until, SimTime::from_ms(100 * (k + 1))));
  }
  sim.bus().unsubscribe(handle);
  rec.hash = state_hash(sim.state());
  return rec;
}

}  // namespace rescuesim::testing
