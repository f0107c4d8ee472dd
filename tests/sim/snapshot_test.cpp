// Snapshot and restore are exact: run on from a snapshot recording every message, restore,
// run again with the same commands, and every message and the state hash come out bitwise the
// same — in the default scenario, and among falling rubble that hits itself and the robot.
// Restoring to an earlier time resumes /clock and /tf at once.

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "robots/rescue_robot.h"
#include "sim/drive_pattern.h"
#include "sim/simulation.h"
#include "support/rig.h"

namespace rescuesim {
namespace {

using testing::default_sim;
using testing::drive;
using testing::Recording;

/// Where two recordings first differ, for the failure message.
std::string first_difference(const Recording& a, const Recording& b) {
  for (std::size_t i = 0; i < std::min(a.messages.size(), b.messages.size()); ++i) {
    if (a.messages[i] != b.messages[i]) return "message " + std::to_string(i) + " (topic " + std::to_string(a.messages[i].first) + ")";
  }
  if (a.messages.size() != b.messages.size()) {
    return "count " + std::to_string(a.messages.size()) + " vs " + std::to_string(b.messages.size());
  }
  return "none";
}

TEST(Snapshot, RestoreReplaysTheDefaultScenarioBitwise) {
  auto sim = default_sim();
  drive(*sim, SimTime::from_seconds(2));
  const State snap = sim->snapshot();
  const Recording first = drive(*sim, SimTime::from_seconds(4));
  ASSERT_GT(first.messages.size(), 1000u);
  sim->restore(snap);
  EXPECT_EQ(state_hash(sim->state()), state_hash(snap));
  const Recording again = drive(*sim, SimTime::from_seconds(4));
  EXPECT_EQ(again.messages, first.messages) << "first difference: " << first_difference(first, again);
  EXPECT_EQ(again.hash, first.hash);
  // and a third time, from a simulation that ran on elsewhere meanwhile
  drive(*sim, SimTime::from_seconds(5));
  sim->restore(snap);
  EXPECT_EQ(drive(*sim, SimTime::from_seconds(4)).hash, first.hash);
}

TEST(Snapshot, RestoreIntoAnotherSimulationOfTheSameScenarioReplaysBitwise) {
  auto a = default_sim();
  auto b = default_sim();
  drive(*a, SimTime::from_seconds(1));
  const State snap = a->snapshot();
  const Recording ra = drive(*a, SimTime::from_seconds(2));
  b->restore(snap);
  const Recording rb = drive(*b, SimTime::from_seconds(2));
  // b never published the first second: compare from the snapshot on
  EXPECT_EQ(rb.messages, ra.messages) << "first difference: " << first_difference(ra, rb);
  EXPECT_EQ(rb.hash, ra.hash);
}

/// A room with boxes stacked and dropped in front of the robot, which drives into them.
std::unique_ptr<Simulation> rubble_sim() {
  WorldSpec w = testing::room_spec(8.0);
  for (int i = 0; i < 6; ++i) {
    RubbleSpec box;
    box.pose = {1.0 + 0.15 * (i % 3), 0.1 * (i / 3) - 0.05, 0.3 * i};
    box.size = {0.25, 0.2, 0.15};
    w.rubble.push_back(box);
  }
  auto sim = std::make_unique<Simulation>(compile_world(w, builtin_models()), SimOptions{});
  // lift the boxes into a tilted tower above the robot's path, awake, so they fall onto each other
  State s = sim->snapshot();
  for (std::size_t i = 0; i < s.dynamics.size(); ++i) {
    s.dynamics[i].X_WB.p.z() += 0.25 + 0.22 * static_cast<double>(i);
    s.dynamics[i].sleep = BodyState::Sleep::awake;
  }
  sim->restore(s);
  return sim;
}

TEST(Snapshot, RestoreReplaysFallingRubbleBitwise) {
  auto sim = rubble_sim();
  drive(*sim, SimTime::from_seconds(0.3));  // boxes in the air, some already hitting each other
  const State snap = sim->snapshot();
  const Recording first = drive(*sim, SimTime::from_seconds(3));
  // the boxes fell (the lowest lies on the floor, 7.5 cm up) and were pushed about
  double lowest = 1e9, furthest = 0;
  for (std::size_t i = 0; i < snap.dynamics.size(); ++i) {
    const BodyState& b = sim->state().dynamics[i];
    lowest = std::min(lowest, b.X_WB.p.z());
    furthest = std::max(furthest, (b.X_WB.p - snap.dynamics[i].X_WB.p).head<2>().norm());
  }
  EXPECT_LT(lowest, 0.08);
  EXPECT_GT(furthest, 0.05);
  sim->restore(snap);
  const Recording again = drive(*sim, SimTime::from_seconds(3));
  EXPECT_EQ(again.messages, first.messages) << "first difference: " << first_difference(first, again);
  EXPECT_EQ(again.hash, first.hash);
}

TEST(Snapshot, RubbleThatFellAsleepStaysAsleepAfterARestore) {
  auto sim = rubble_sim();
  sim->step_until(SimTime::from_seconds(6));  // the robot stands; the boxes come to rest and sleep
  int asleep = 0;
  for (const auto& b : sim->state().dynamics) asleep += b.sleep == BodyState::Sleep::asleep;
  ASSERT_GT(asleep, 0);
  const State snap = sim->snapshot();
  sim->restore(snap);
  for (std::size_t i = 0; i < snap.dynamics.size(); ++i) EXPECT_EQ(sim->state().dynamics[i].sleep, snap.dynamics[i].sleep) << i;
  sim->step();
  // a sleeping body does not move: its pose is bitwise what it was
  for (std::size_t i = 0; i < snap.dynamics.size(); ++i) {
    if (snap.dynamics[i].sleep == BodyState::Sleep::asleep) {
      EXPECT_EQ(sim->state().dynamics[i].X_WB.p, snap.dynamics[i].X_WB.p) << i;
    }
  }
}

TEST(Snapshot, RestoreToAnEarlierTimeResumesClockAndTfAtOnce) {
  WorldSpec w = testing::room_spec();
  Simulation sim(compile_world(w, builtin_models()), SimOptions{});
  sim.step_until(SimTime::from_seconds(1));
  const State at1 = sim.snapshot();
  sim.step_until(SimTime::from_seconds(3));
  sim.restore(at1);
  std::map<std::string, int> count;
  bool live = false;  // not the latched messages subscribe replays
  sim.bus().subscribe("", [&](const Topic& t, const msg::Message&) { count[t.name] += live; });
  live = true;
  // 0.1 s = 20 steps after the restore: /clock every step (20), /tf with moving joints at 50 Hz
  // (5) plus the odometry transform at its 50 Hz (5), as in any 0.1 s
  sim.step_until(SimTime::from_ms(1100));
  EXPECT_EQ(count["/clock"], 20);
  EXPECT_EQ(count["/tf"], 10);
  EXPECT_EQ(count["/scan"], 1);  // 10 Hz: the one at 1.1 s
  EXPECT_EQ(count["/tf_static"], 0);  // already out at t = 0
}

TEST(Snapshot, RestoreToTheStartPublishesTheStartAgain) {
  WorldSpec w = testing::room_spec();
  Simulation sim(compile_world(w, builtin_models()), SimOptions{});
  const State start = sim.snapshot();
  sim.step_until(SimTime::from_seconds(1));
  sim.restore(start);
  int tf_static = 0, clock = 0;
  bool live = false;  // not the latched /tf_static that subscribe replays
  sim.bus().subscribe("/tf_static", [&](const Topic&, const msg::Message&) { tf_static += live; });
  live = true;
  sim.bus().subscribe("/clock", [&](const Topic&, const msg::Message&) { ++clock; });
  sim.step();
  EXPECT_EQ(tf_static, 1);
  EXPECT_EQ(clock, 2);  // t = 0 and t = 5 ms
}

}  // namespace
}  // namespace rescuesim
