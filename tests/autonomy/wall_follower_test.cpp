#include "autonomy/wall_follower.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "autonomy/kinematic_sim.h"
#include "core/rng.h"

namespace rescuesim::autonomy {
namespace {

using testing::Segment;

constexpr float kInf = std::numeric_limits<float>::infinity();

// a 360-beam full-circle scan of zero-thickness segments from sensor pose X_WS
msg::LaserScan scan_of(const std::vector<Segment>& walls, const Pose2& X_WS = {}) {
  msg::LaserScan s;
  s.angle_min = static_cast<float>(-M_PI);
  s.angle_increment = static_cast<float>(2 * M_PI / 360);
  s.angle_max = s.angle_min + 359 * s.angle_increment;
  s.range_min = 0.05f;
  s.range_max = 10.0f;
  for (int i = 0; i < 360; ++i) {
    const double a = X_WS.yaw + s.angle_min + i * static_cast<double>(s.angle_increment);
    const double r = testing::ray_cast(X_WS.position(), Vec2(std::cos(a), std::sin(a)), walls);
    s.ranges.push_back(r < s.range_max ? static_cast<float>(r) : kInf);
  }
  return s;
}

// a long straight wall along x at height y (m); the robot stands at the origin facing +x
std::vector<Segment> wall_at(double y) { return {{{-10.0, y}, {10.0, y}}}; }

WallFollowerConfig with_target(double target, WallSide side = WallSide::right) {
  WallFollowerConfig c;
  c.target_distance = target;
  c.side = side;
  return c;
}

TEST(WallFollower, TooCloseToTheRightWallTurnsLeftAway) {
  WallFollower wf(with_target(0.5));
  const msg::Twist t = wf.command(scan_of(wall_at(-0.4)));
  EXPECT_GT(t.angular.z(), 0.05);  // counter-clockwise: left, away from the wall
  EXPECT_GT(t.linear.x(), 0.0);
  EXPECT_EQ(wf.state(), WallFollowerState::following);
  EXPECT_NEAR(wf.wall_distance(), 0.4, 1e-3);
}

TEST(WallFollower, TooFarFromTheRightWallTurnsRightTowardIt) {
  WallFollower wf(with_target(0.5));
  const msg::Twist t = wf.command(scan_of(wall_at(-0.7)));
  EXPECT_LT(t.angular.z(), -0.05);  // clockwise: right, toward the wall
  EXPECT_GT(t.linear.x(), 0.0);
}

TEST(WallFollower, AtTheTargetDistanceDrivesStraightAtFullSpeed) {
  WallFollower wf(with_target(0.5));
  const msg::Twist t = wf.command(scan_of(wall_at(-0.5)));
  EXPECT_NEAR(t.angular.z(), 0.0, 0.03);
  EXPECT_GT(t.linear.x(), 0.45);
  EXPECT_LE(t.linear.x(), 0.5);
}

TEST(WallFollower, LeftHandFollowingMirrorsTheSigns) {
  WallFollower wf(with_target(0.5, WallSide::left));
  EXPECT_LT(wf.command(scan_of(wall_at(0.4))).angular.z(), -0.05);
  EXPECT_GT(wf.command(scan_of(wall_at(0.7))).angular.z(), 0.05);
  // and a right-hand follower does not take a left wall for its own
  WallFollower right(with_target(0.5));
  right.command(scan_of(wall_at(0.4)));
  EXPECT_TRUE(std::isinf(right.wall_distance()));
}

TEST(WallFollower, HeadingIntoTheWallTurnsAway) {
  // at the target distance but yawed 20 degrees toward the right wall
  WallFollower wf(with_target(0.5));
  const double yaw = -20 * M_PI / 180;
  const msg::Twist t = wf.command(scan_of(wall_at(-0.5), {0, 0, yaw}));
  EXPECT_GT(t.angular.z(), 0.2);
}

TEST(WallFollower, SomethingAheadSlowsAndTurnsAwayFromTheWallSide) {
  std::vector<Segment> walls = wall_at(-0.5);
  walls.push_back({{1.0, -1.0}, {1.0, 2.0}});  // 1 m ahead: 0.65 m of travel for the 0.35 m disc
  WallFollower wf(with_target(0.5));
  const msg::Twist slow = wf.command(scan_of(walls));
  EXPECT_EQ(wf.state(), WallFollowerState::avoiding);
  EXPECT_NEAR(wf.front_distance(), 0.65, 1e-3);
  EXPECT_LT(slow.linear.x(), 0.6 * wf.config().max_linear);
  EXPECT_GT(slow.angular.z(), 0.2);

  walls.back() = {{0.5, -1.0}, {0.5, 2.0}};  // 0.15 m of travel: stop and turn on the spot
  const msg::Twist stop = wf.command(scan_of(walls));
  EXPECT_EQ(wf.state(), WallFollowerState::blocked);
  EXPECT_EQ(stop.linear.x(), 0.0);
  EXPECT_GT(stop.angular.z(), 0.5);
}

TEST(WallFollower, WhereTheWallEndsItTurnsRoundTheEndSlowly) {
  // the right wall ends abeam of the robot: round its end, toward the wall side
  WallFollower wf(with_target(0.5));
  const msg::Twist t = wf.command(scan_of({{{-10.0, -0.5}, {0.0, -0.5}}}));
  EXPECT_EQ(wf.state(), WallFollowerState::turning_corner);
  EXPECT_LT(t.angular.z(), -0.3);
  EXPECT_LE(t.linear.x(), 0.5 * wf.config().max_linear + 1e-9);
  EXPECT_GT(t.linear.x(), 0.0);
}

TEST(WallFollower, NoWallDrivesStraightToFindOne) {
  WallFollower wf(with_target(0.5));
  const msg::Twist t = wf.command(scan_of({}));
  EXPECT_EQ(wf.state(), WallFollowerState::seeking);
  EXPECT_EQ(t.angular.z(), 0.0);
  EXPECT_DOUBLE_EQ(t.linear.x(), wf.config().max_linear);
}

TEST(WallFollower, Rep117NegativeInfinityMeansTooCloseAndNaNMeansNothing) {
  WallFollower wf(with_target(0.5));
  msg::LaserScan s = scan_of({});
  s.ranges.assign(s.ranges.size(), -kInf);
  const msg::Twist close = wf.command(s);
  EXPECT_EQ(wf.state(), WallFollowerState::blocked);
  EXPECT_EQ(close.linear.x(), 0.0);

  s.ranges.assign(s.ranges.size(), std::numeric_limits<float>::quiet_NaN());
  wf.reset();
  const msg::Twist nothing = wf.command(s);
  EXPECT_EQ(wf.state(), WallFollowerState::seeking);
  EXPECT_GT(nothing.linear.x(), 0.0);

  s.ranges.clear();
  EXPECT_EQ(wf.command(s).linear.x(), 0.0);
  EXPECT_EQ(wf.state(), WallFollowerState::no_data);
}

TEST(WallFollower, CommandsStayWithinTheLimits) {
  WallFollowerConfig c = with_target(0.5);
  c.max_linear = 0.3;
  c.max_angular = 0.8;
  WallFollower wf(c);
  const std::vector<Segment> maze = testing::carve_maze(4, 1.5, 3);
  Rng rng(3, "wall follower limits");
  for (int i = 0; i < 300; ++i) {
    const Pose2 X{rng.uniform(0.2, 5.8), rng.uniform(0.2, 5.8), rng.uniform(-M_PI, M_PI)};
    const msg::Twist t = wf.command(scan_of(maze, X));
    EXPECT_GE(t.linear.x(), 0.0);
    EXPECT_LE(t.linear.x(), 0.3);
    EXPECT_LE(std::abs(t.angular.z()), 0.8);
  }
}

TEST(WallFollower, MountingPoseIsTakenIntoAccount) {
  // a laser mounted backwards 0.1 m ahead of the base sees the same world turned round
  const Pose2 X_BS{0.1, 0.0, M_PI};
  WallFollowerConfig c = with_target(0.5);
  c.X_BS = X_BS;
  WallFollower mounted(c), plain(with_target(0.5));
  const std::vector<Segment> walls = wall_at(-0.7);
  const msg::Twist a = mounted.command(scan_of(walls, Pose2{} * X_BS));
  const msg::Twist b = plain.command(scan_of(walls));
  EXPECT_NEAR(a.angular.z(), b.angular.z(), 0.02);
  EXPECT_NEAR(a.linear.x(), b.linear.x(), 0.02);
  EXPECT_LT(a.angular.z(), 0.0);
}

TEST(WallFollower, SettlesAtTheTargetDistanceAlongAWall) {
  // closed loop with the kinematic simulator: start 1 m from a long wall on the right
  testing::KinematicSim sim({{{-1.0, 0.0}, {60.0, 0.0}}}, {0.0, 1.05, 0.0}, {}, 0.35);
  WallFollower wf(with_target(0.55));
  for (int k = 0; k < 300; ++k) sim.step(wf.command(sim.scan(SimTime::from_ms(50) * k)), 0.05);
  // the surface is 0.05 m above the centre line (0.1 m thick wall)
  EXPECT_NEAR(sim.pose().y - 0.05, 0.55, 0.03);
  EXPECT_NEAR(sim.pose().yaw, 0.0, 0.05);
  EXPECT_EQ(sim.collisions(), 0);
}

}  // namespace
}  // namespace rescuesim::autonomy
