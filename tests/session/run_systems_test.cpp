// A run is a Simulation with run systems stepped around it (sim/run_system.h): a system added to
// a Session sees every step from both sides, in order, and its memory is part of snapshots.

#include <gtest/gtest.h>

#include <any>
#include <utility>
#include <vector>

#include "robots/rescue_robot.h"
#include "session/session.h"

namespace rescuesim {
namespace {

/// Writes down when it was called, and counts the steps it saw (its memory).
struct Probe final : RunSystem {
  std::vector<std::pair<char, SimTime>> calls;  // ('<' pre_step, '>' post_step, the sim time then)
  int steps = 0;
  std::string_view system_name() const override { return "probe"; }
  void pre_step(Simulation& sim) override { calls.emplace_back('<', sim.time()); }
  void post_step(Simulation& sim) override {
    calls.emplace_back('>', sim.time());
    ++steps;
  }
  std::any save() const override { return steps; }
  void load(const std::any& memory, Simulation&) override { steps = std::any_cast<int>(memory); }
};

/// The example of docs/architecture.md, section 4: stops every robot standing too close to a victim.
struct KeepClear final : rescuesim::RunSystem {
  double radius = 0.5;  // m
  std::string_view system_name() const override { return "keep-clear"; }
  void post_step(rescuesim::Simulation& sim) override {
    const rescuesim::State& s = sim.state();
    for (std::size_t r = 0; r < s.robots.size(); ++r) {
      for (const auto& v : sim.world().victims) {
        const double d = (s.robots[r].base.X_WB.p.head<2>() - v.centre.head<2>()).norm();
        if (d < radius) sim.command_velocity(static_cast<int>(r), {});  // for the next step
      }
    }
  }
};

SessionOptions no_cameras() {
  SessionOptions o;
  o.cameras = false;
  return o;
}

TEST(RunSystems, AnAddedSystemSeesEveryStepFromBothSides) {
  const ModelMap models = builtin_models();
  Session session(default_scenario(models), models, no_cameras());
  auto probe = std::make_unique<Probe>();
  Probe& p = *probe;
  session.add_system(std::move(probe));
  const SimTime dt = SimTime::from_seconds(session.sim().dt());
  session.step_until(dt + dt + dt);
  // three steps: before each the time it starts from, after each the time it reached
  ASSERT_EQ(p.calls.size(), 6u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(p.calls[2 * k].first, '<');
    EXPECT_EQ(p.calls[2 * k].second.ns, k * dt.ns);
    EXPECT_EQ(p.calls[2 * k + 1].first, '>');
    EXPECT_EQ(p.calls[2 * k + 1].second.ns, (k + 1) * dt.ns);
  }
  EXPECT_EQ(p.steps, 3);
}

TEST(RunSystems, AnAddedSystemsMemoryComesBackWithARestore) {
  const ModelMap models = builtin_models();
  Session session(default_scenario(models), models, no_cameras());
  auto probe = std::make_unique<Probe>();
  Probe& p = *probe;
  session.add_system(std::move(probe));
  const SimTime dt = SimTime::from_seconds(session.sim().dt());
  session.step_until(SimTime{4 * dt.ns});
  const SessionSnapshot snap = session.snapshot();
  session.step_until(SimTime{10 * dt.ns});
  EXPECT_EQ(p.steps, 10);
  session.restore(snap);
  EXPECT_EQ(p.steps, 4);
  EXPECT_EQ(session.sim().time().ns, 4 * dt.ns);
}

TEST(RunSystems, TheArchitecturePagesExampleStopsTheRobotsTheBuiltInControllersDrive) {
  // the explorer drives the default scenario's robot off at once; KeepClear runs after it and
  // its stop is the command that stands (with a radius that takes in the whole world)
  const ModelMap models = builtin_models();
  double driven[2] = {0, 0};
  for (int with = 0; with < 2; ++with) {
    Session session(default_scenario(models), models, no_cameras());
    if (with) {
      auto keep_clear = std::make_unique<KeepClear>();
      keep_clear->radius = 1000;
      session.add_system(std::move(keep_clear));
    }
    session.step_until(SimTime::from_seconds(3));
    driven[with] = session.sim().state().robots[0].distance;
  }
  EXPECT_GT(driven[0], 0.2);
  EXPECT_LT(driven[1], 0.01);
}

}  // namespace
}  // namespace rescuesim
