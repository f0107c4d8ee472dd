// Physics groups (PhysicsOptions::groups): robots spread over independent Bullet worlds still
// meet when they drive into each other, and the run is the same whatever the thread count.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/parallel.h"
#include "support/rig.h"

namespace rescuesim {
namespace {

using testing::Rig;
using testing::room_spec;

/// A 10 m room with robot "robot" at (-1.5, 0) facing east and "robot2" at (1.5, 0) facing west.
WorldSpec face_to_face() {
  WorldSpec spec = room_spec(10.0, {-1.5, 0, 0});
  RobotPlacement b;
  b.name = "robot2";
  b.start = {1.5, 0, M_PI};
  spec.robots.push_back(b);
  return spec;
}

/// Holds every robot's cmd_vel at (v, 0) for `seconds`; returns the least distance between the
/// first two robots' bases over that time.
double drive_all(Rig& rig, double v, double seconds) {
  double closest = 1e9;
  const long n = std::lround(seconds / rig.dt());
  for (long i = 0; i < n; ++i) {
    for (auto& r : rig.state.robots) {
      r.cmd_linear = Vec3(v, 0, 0);
      r.cmd_angular = Vec3::Zero();
      r.cmd_time = rig.state.time;
    }
    rig.step();
    closest = std::min(closest, (rig.state.robots[0].base.X_WB.p - rig.state.robots[1].base.X_WB.p).head<2>().norm());
  }
  return closest;
}

TEST(PhysicsGroups, RobotsOfDifferentHomeWorldsStillMeetWhenTheyDriveIntoEachOther) {
  PhysicsOptions o;
  o.groups = 2;  // robot 0 lives in world 0, robot 1 in world 1, until they come close
  Rig rig(face_to_face(), o);
  EXPECT_EQ(rig.physics->stats().groups, 2);
  // 3 m apart at 0.5 m/s each: the 0.6 m chassis meet after (3 - 0.6) / 1 = 2.4 s, in the middle
  const double closest = drive_all(rig, 0.5, 4.0);
  // in separate worlds they would drive through each other (closest near 0); in one, their
  // bumpers stop them a chassis length apart
  EXPECT_GT(closest, 0.55);
  EXPECT_LT(closest, 0.65);
  // and they stay on their line, front to front
  EXPECT_NEAR(rig.state.robots[0].base.X_WB.p.y(), 0.0, 0.05);
  EXPECT_NEAR(rig.state.robots[1].base.X_WB.p.y(), 0.0, 0.05);
  const auto& touching = rig.state.robots[0].touching;
  EXPECT_NE(std::find(touching.begin(), touching.end(), "robot2"), touching.end());
}

TEST(PhysicsGroups, ARobotPushesRubbleOfAnotherWorld) {
  // robot 0 lives in world 0; the box is entity 1 (robots first, then rubble), so world 1
  WorldSpec spec = room_spec(10.0, {-1.5, 0, 0});
  RubbleSpec box;
  box.pose = {0, 0, 0};
  box.size = {0.3, 0.6, 0.2};
  box.mass = 2.0;
  spec.rubble.push_back(box);
  PhysicsOptions o;
  o.groups = 2;
  Rig rig(spec, o);
  const double x0 = rig.state.dynamics[0].X_WB.p.x();
  // the bumper (0.3 m ahead of the base) reaches the box's face (0.15 m before its centre) after
  // 1.05 m; 4 s at 0.5 m/s drives 2 m, so the box is pushed about 0.95 m
  rig.drive(0.5, 0, 4.0);
  EXPECT_GT(rig.state.dynamics[0].X_WB.p.x() - x0, 0.5);
  // and it stays ahead of the robot: the bumper never passes through it
  EXPECT_GT(rig.state.dynamics[0].X_WB.p.x() - rig.robot().base.X_WB.p.x(), 0.4);
}

TEST(PhysicsGroups, OneWorldGivesTheSameMeeting) {
  PhysicsOptions o;
  o.groups = 1;
  Rig rig(face_to_face(), o);
  EXPECT_EQ(rig.physics->stats().groups, 1);
  const double closest = drive_all(rig, 0.5, 4.0);
  EXPECT_GT(closest, 0.55);
  EXPECT_LT(closest, 0.65);
}

TEST(PhysicsGroups, EightRobotsBelowEightAreOneWorldAtEightTwo) {
  // automatic: one world below 8 robots, then one per 8 robots
  WorldSpec spec = room_spec(20.0, {-8, -8, 0});
  for (int k = 1; k < 7; ++k) {
    RobotPlacement r;
    r.name = "r";
    r.name += std::to_string(k);
    r.start = {-8.0 + 2 * k, -8, 0};
    spec.robots.push_back(r);
  }
  EXPECT_EQ(Rig(spec).physics->stats().groups, 1);
  RobotPlacement last;
  last.name = "r7";
  last.start = {6, -8, 0};
  spec.robots.push_back(last);
  EXPECT_EQ(Rig(spec).physics->stats().groups, 2);
}

/// Eight robots in four worlds, pairs driving into each other (so robots change worlds), at
/// `threads` worker threads: the state hash after 3 s.
std::uint64_t eight_robots_meeting(int threads) {
  WorldSpec spec = room_spec(20.0, {-1.5, -6, 0});
  spec.robots.clear();
  for (int pair = 0; pair < 4; ++pair) {
    const double y = -6.0 + 4.0 * pair;
    RobotPlacement a, b;
    a.name = "a";
    a.name += std::to_string(pair);
    a.start = {-1.5, y, 0};
    b.name = "b";
    b.name += std::to_string(pair);
    b.start = {1.5 + 0.3 * pair, y + 0.1 * pair, M_PI};
    spec.robots.push_back(a);
    spec.robots.push_back(b);
  }
  PhysicsOptions o;
  o.groups = 4;
  set_worker_threads(threads);
  Rig rig(spec, o);
  drive_all(rig, 0.6, 3.0);
  set_worker_threads(0);
  return state_hash(rig.state);
}

TEST(PhysicsGroups, TheThreadCountDoesNotChangeTheRun) {
  const std::uint64_t one = eight_robots_meeting(1);
  EXPECT_EQ(eight_robots_meeting(2), one);
  EXPECT_EQ(eight_robots_meeting(4), one);
}

TEST(PhysicsGroups, TwoRestoresOfOneStateStepOnAlike) {
  PhysicsOptions o;
  o.groups = 2;
  Rig rig(face_to_face(), o);
  drive_all(rig, 0.5, 2.3);  // almost touching: both robots in world 0 now
  const State saved = rig.state;
  auto step_on = [&] {
    rig.physics->restore(saved);
    rig.state = saved;
    drive_all(rig, 0.5, 1.0);
    return state_hash(rig.state);
  };
  const std::uint64_t first = step_on();
  EXPECT_EQ(step_on(), first);
}

}  // namespace
}  // namespace rescuesim
