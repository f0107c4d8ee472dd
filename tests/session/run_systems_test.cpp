// A run is a Simulation with run systems stepped around it (sim/run_system.h): a system added to
// a Session sees every step from both sides, in order, its memory is part of snapshots, and it
// writes its outputs after the built-in systems wrote theirs (sim/run_outputs.h).

#include <gtest/gtest.h>

#include <any>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

#include "core/atomic_file.h"
#include "robots/rescue_robot.h"
#include "session/session.h"
#include "sim/run_outputs.h"
#include "viz/canvas.h"

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
    for (rescuesim::RobotIndex r : sim.world().robot_indices()) {
      for (const auto& v : sim.world().victims) {
        const double d = (s.robot(r).base.X_WB.p.head<2>() - v.centre.head<2>()).norm();
        if (d < radius) sim.command_velocity(r, {});  // for the next step
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

/// At the end of a run: looks at what the built-in systems left (trajectory.csv, the path's end
/// on the overview) and writes a file of its own.
struct Painter final : RunSystem {
  // what it saw (mutable: write_outputs is const, and this is a probe)
  mutable bool trajectory_written = false;
  mutable Rgb8 at_path_end{255, 255, 255};
  std::string_view system_name() const override { return "painter"; }
  void write_outputs(const Simulation& sim, RunOutputs& out) const override {
    trajectory_written = std::filesystem::exists(out.dir / "trajectory.csv");
    if (trajectory_written) {
      // the last sample: t,robot,x,y,...
      std::ifstream in(out.dir / "trajectory.csv");
      std::string line, last;
      while (std::getline(in, line)) last = line;
      std::stringstream fields(last);
      std::string t, robot, x, y;
      std::getline(fields, t, ',');
      std::getline(fields, robot, ',');
      std::getline(fields, x, ',');
      std::getline(fields, y, ',');
      const Vec2 px = out.frame.to_px({std::stod(x), std::stod(y)});
      at_path_end = out.overview.at(static_cast<int>(std::floor(px.x())), static_cast<int>(std::floor(px.y())));
    }
    write_file_atomic(out.dir / "painter.txt", out.run_name + " " + std::to_string(sim.state().step) + "\n");
  }
};

TEST(RunSystems, AnAddedSystemWritesItsOutputsAfterTheBuiltInOnes) {
  const ModelMap models = builtin_models();
  Session session(default_scenario(models), models, no_cameras());
  auto painter = std::make_unique<Painter>();
  const Painter& p = *painter;
  session.add_system(std::move(painter));
  session.step_until(SimTime::from_seconds(2));
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("rs-run-outputs-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir / "sensors");
  session.write_outputs(dir, session.result());
  // the recorder wrote before it, and drew the path's end as a dark green dot of radius 5 px
  EXPECT_TRUE(p.trajectory_written);
  EXPECT_EQ(p.at_path_end.r, 20);
  EXPECT_EQ(p.at_path_end.g, 120);
  EXPECT_EQ(p.at_path_end.b, 40);
  // its own file: the scenario's name and the steps of 2 s
  std::ifstream in(dir / "painter.txt");
  std::string name;
  std::int64_t steps = 0;
  in >> name >> steps;
  EXPECT_EQ(name, session.scenario().name);
  EXPECT_EQ(steps, session.sim().state().step);
  EXPECT_EQ(steps, std::llround(2.0 / session.sim().dt()));
  EXPECT_TRUE(std::filesystem::exists(dir / "overview.png"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace rescuesim
