// Robots and loose bodies added and removed while the simulation runs (Simulation::add_robot,
// remove_robot, add_body, remove_spawned): what SpawnEntity and DeleteEntity stand on.

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "core/parallel.h"
#include "msgs/digest.h"
#include "robots/rescue_robot.h"
#include "sim/simulation.h"
#include "support/rig.h"

namespace rescuesim {
namespace {

using testing::room_spec;

Simulation make_sim() { return Simulation(compile_world(room_spec(), builtin_models()), SimOptions{}); }

/// The rescue robot as SpawnEntity makes it: named, namespaced, placed at (x, y).
RobotInstance spawned_robot(const std::string& name, double x, double y) {
  RobotInstance r = place_robot(name, rescue_robot(), Pose3{Vec3(x, y, 0), Quat::Identity()});
  r.spawned = true;
  r.ns = name;
  return r;
}

const Topic* find_topic(const Bus& bus, const std::string& name) {
  for (const Topic& t : bus.topics()) {
    if (t.name == name) return &t;
  }
  return nullptr;
}

/// Holds cmd_vel (v, 0) on `robot` for `seconds`, re-sent every 0.1 s.
void drive(Simulation& sim, RobotIndex robot, double v, double seconds) {
  const SimTime end = sim.time() + SimTime::from_seconds(seconds);
  while (sim.time() < end) {
    msg::Twist t;
    t.linear.x() = v;
    ASSERT_TRUE(sim.command_velocity(robot, t));
    sim.step_until(std::min(end, sim.time() + SimTime::from_ms(100)));
  }
}

TEST(Spawn, ASpawnedRobotHasItsTopicsUnderItsNamespaceAndDrives) {
  Simulation sim = make_sim();
  std::map<std::string, std::vector<SimTime>> stamps;
  sim.bus().subscribe("", [&](const Topic& t, const msg::Message& m) { stamps[t.name].push_back(msg::stamp_of(m)); });
  int layout_calls = 0;
  sim.bus().watch_layout([&] { ++layout_calls; });
  sim.step_until(SimTime::from_seconds(1.0));
  const SimTime spawned_at = sim.time();
  const std::uint64_t version = sim.bus().layout_version();

  const RobotIndex p3at = sim.add_robot(spawned_robot("p3at", 3, 3));
  EXPECT_EQ(p3at, RobotIndex(1));
  EXPECT_EQ(sim.world().robots.size(), 2u);
  EXPECT_EQ(sim.state().robots.size(), 2u);
  EXPECT_EQ(layout_calls, 1);
  EXPECT_EQ(sim.bus().layout_version(), version + 1);
  // the scenario's robot keeps its names (one robot: at the root); the new one is under /p3at
  ASSERT_NE(find_topic(sim.bus(), "/scan"), nullptr);
  const Topic* scan = find_topic(sim.bus(), "/p3at/scan");
  ASSERT_NE(scan, nullptr);
  EXPECT_EQ(scan->robot, RobotIndex(1));
  EXPECT_EQ(sim.topic_name(RobotIndex(1), "cmd_vel"), "/p3at/cmd_vel");
  EXPECT_EQ(sim.frame_name(RobotIndex(1), "base_link"), "p3at/base_link");
  EXPECT_EQ(sim.topic_name(RobotIndex(0), "cmd_vel"), "/cmd_vel");

  // its laser is due at once (sampled after the next step, 5 ms on), then on the 0.1 s grid
  // from the spawn: 1.005, 1.1, ..., 2.0 s is 11 scans
  sim.step_until(spawned_at + SimTime::from_seconds(1.0));
  ASSERT_EQ(stamps["/p3at/scan"].size(), 11u);
  EXPECT_EQ(stamps["/p3at/scan"].front().ns, spawned_at.ns + 5'000'000);
  EXPECT_EQ(stamps["/p3at/scan"][1].ns, spawned_at.ns + 100'000'000);
  EXPECT_EQ(stamps["/scan"].size(), 21u);  // the first robot's schedule goes on untouched
  // it was placed clear of the floor and came to rest at the height of the same model beside it
  EXPECT_NEAR(sim.state().robots[1].base.X_WB.p.z(), sim.state().robots[0].base.X_WB.p.z(), 0.003);
  EXPECT_NEAR(sim.state().robots[1].base.X_WB.p.x(), 3.0, 0.01);

  // cmd_vel at 0.3 m/s for 3 s moves it about 0.9 m less the speed-up; the other robot stays
  const Vec3 before = sim.state().robots[1].base.X_WB.p, other = sim.state().robots[0].base.X_WB.p;
  drive(sim, p3at, 0.3, 3.0);
  const double moved = (sim.state().robots[1].base.X_WB.p - before).norm();
  EXPECT_GT(moved, 0.7);
  EXPECT_LT(moved, 0.91);
  EXPECT_LT((sim.state().robots[0].base.X_WB.p - other).norm(), 0.01);
  // its odometry starts at zero where it was spawned
  EXPECT_NEAR(sim.state().robots[1].odom.x, moved, 0.05);
}

TEST(Spawn, DeletingARobotRetiresItsTopicsAndFrames) {
  Simulation sim = make_sim();
  sim.step_until(SimTime::from_seconds(0.5));
  const RobotIndex a = sim.add_robot(spawned_robot("a", 3, 3));
  const RobotIndex b = sim.add_robot(spawned_robot("b", -3, -3));
  ASSERT_EQ(a, RobotIndex(1));
  ASSERT_EQ(b, RobotIndex(2));
  sim.step_until(SimTime::from_seconds(1.0));
  std::map<std::string, int> counts;
  std::set<std::string> tf_frames;
  sim.bus().subscribe("", [&](const Topic& t, const msg::Message& m) {
    ++counts[t.name];
    if (t.name == "/tf") {
      for (const auto& tr : std::get<msg::TFMessage>(m).transforms) tf_frames.insert(tr.child_frame_id);
    }
  });
  sim.remove_robot(a);
  EXPECT_EQ(sim.world().robots.size(), 2u);
  EXPECT_EQ(sim.world().robots[1].name, "b");
  EXPECT_TRUE(find_topic(sim.bus(), "/a/scan")->retired);
  EXPECT_FALSE(find_topic(sim.bus(), "/b/scan")->retired);
  EXPECT_EQ(find_topic(sim.bus(), "/b/scan")->robot, RobotIndex(1));  // b moved down one index
  sim.step_until(SimTime::from_seconds(2.0));
  EXPECT_EQ(counts["/a/scan"], 0);
  EXPECT_EQ(counts["/b/scan"], 10);
  EXPECT_EQ(tf_frames.count("a/base_link"), 0u);
  EXPECT_EQ(tf_frames.count("b/base_link"), 1u);
  // b still drives, by its new index
  const double x = sim.state().robots[1].base.X_WB.p.x();
  drive(sim, RobotIndex(1), 0.3, 2.0);
  EXPECT_GT(sim.state().robots[1].base.X_WB.p.x() - x, 0.4);
  // a scenario robot cannot be removed; a name comes back after its robot went
  EXPECT_DEATH_IF_SUPPORTED(sim.remove_robot(RobotIndex(0)), "spawned robot");
  EXPECT_EQ(sim.add_robot(spawned_robot("a", 3, 3)), RobotIndex(2));
  EXPECT_FALSE(find_topic(sim.bus(), "/a/scan")->retired);
}

TEST(Spawn, ASpawnedBoxFallsAsGravitySays) {
  Simulation sim = make_sim();
  sim.step_until(SimTime::from_seconds(0.5));
  DynamicObject box;
  box.name = "box";
  box.geometry = Geometry::box(Vec3(0.2, 0.2, 0.2));
  box.X_WO = Pose3{Vec3(-4, 4, 1.0), Quat::Identity()};
  box.mass = 2.0;
  box.spawned = true;
  const std::size_t i = sim.add_body(box);
  ASSERT_EQ(i, sim.base_bodies());
  // free fall from z = 1: after 0.3 s z = 1 - g 0.3^2 / 2 = 0.5586 m
  sim.step_until(SimTime::from_seconds(0.8));
  EXPECT_NEAR(sim.state().dynamics[i].X_WB.p.z(), 1.0 - 0.5 * 9.81 * 0.09, 0.01);
  // it lands (0.43 s of fall) and rests on its face: centre at half its height
  sim.step_until(SimTime::from_seconds(2.5));
  EXPECT_NEAR(sim.state().dynamics[i].X_WB.p.z(), 0.1, 0.005);
  sim.remove_body(i);
  EXPECT_EQ(sim.world().dynamics.size(), sim.base_bodies());
  sim.step_until(SimTime::from_seconds(3.0));
}

/// The run of the determinism tests: spawn, drive, delete, spawn a box, at `threads` threads.
std::uint64_t spawning_run(int threads) {
  set_worker_threads(threads);
  Simulation sim = make_sim();
  sim.step_until(SimTime::from_seconds(0.5));
  const RobotIndex r = sim.add_robot(spawned_robot("p3at", 2, -2));
  drive(sim, r, 0.4, 1.0);
  DynamicObject box;
  box.name = "box";
  box.geometry = Geometry::box(Vec3(0.3, 0.3, 0.3));
  box.X_WO = Pose3{Vec3(3.5, -2, 0.5), Quat::Identity()};
  box.spawned = true;
  sim.add_body(box);
  drive(sim, r, 0.4, 2.0);
  sim.remove_robot(r);
  sim.step_until(SimTime::from_seconds(4.0));
  set_worker_threads(0);
  return state_hash(sim.state());
}

TEST(Spawn, TheSameSpawnsGiveTheSameStateAtAnyThreadCount) {
  const std::uint64_t one = spawning_run(1);
  EXPECT_EQ(spawning_run(1), one);
  EXPECT_EQ(spawning_run(2), one);
}

TEST(Spawn, RestoringTheStartRemovesWhatWasSpawned) {
  Simulation sim = make_sim();
  const State start = sim.snapshot();
  const std::uint64_t start_hash = state_hash(start);
  sim.step_until(SimTime::from_seconds(0.5));
  sim.add_robot(spawned_robot("p3at", 3, 3));
  DynamicObject box;
  box.name = "box";
  box.geometry = Geometry::box(Vec3(0.2, 0.2, 0.2));
  box.X_WO = Pose3{Vec3(-4, 4, 0.5), Quat::Identity()};
  box.spawned = true;
  sim.add_body(box);
  sim.step_until(SimTime::from_seconds(1.0));
  sim.restore(start);
  EXPECT_EQ(sim.world().robots.size(), 1u);
  EXPECT_EQ(sim.world().dynamics.size(), sim.base_bodies());
  EXPECT_TRUE(find_topic(sim.bus(), "/p3at/scan")->retired);
  EXPECT_EQ(state_hash(sim.state()), start_hash);
  // and the run from there is the run of a fresh simulation
  Simulation fresh = make_sim();
  sim.step_until(SimTime::from_seconds(1.0));
  fresh.step_until(SimTime::from_seconds(1.0));
  EXPECT_EQ(state_hash(sim.state()), state_hash(fresh.state()));
}

TEST(BusLayout, RetiredTopicsDropTheirLatchedMessageAndComeBackWhenAdvertisedAgain) {
  Bus bus;
  const TopicId t = bus.advertise("/a/robot_description", "std_msgs/String", 0, true, RobotIndex(1));
  msg::String s;
  s.data = "<robot/>";
  bus.publish(t, s);
  int late = 0;
  bus.retire(t);
  EXPECT_TRUE(bus.topic(t).retired);
  const SubscriptionId sub = bus.subscribe("/a/robot_description", [&](const Topic&, const msg::Message&) { ++late; });
  EXPECT_EQ(late, 0);  // nothing latched any more
  bus.unsubscribe(sub);
  EXPECT_EQ(bus.advertise("/a/robot_description", "std_msgs/String", 0, true, RobotIndex(2)), t);
  EXPECT_FALSE(bus.topic(t).retired);
  EXPECT_EQ(bus.topic(t).robot, RobotIndex(2));
  std::vector<int> calls;
  const SubscriptionId w1 = bus.watch_layout([&] { calls.push_back(1); });
  bus.watch_layout([&] { calls.push_back(2); });
  bus.layout_changed();
  bus.unsubscribe(w1);
  bus.layout_changed();
  EXPECT_EQ(calls, (std::vector<int>{1, 2, 2}));
  EXPECT_EQ(bus.layout_version(), 2u);
}

}  // namespace
}  // namespace rescuesim
