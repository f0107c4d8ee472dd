#include "autonomy/path_follower.h"

#include <gtest/gtest.h>

#include <cmath>

#include "autonomy/kinematic_sim.h"

namespace rescuesim::autonomy {
namespace {

// distance (m) from p to the polyline
double distance_to_path(const Vec2& p, const std::vector<Vec2>& path) {
  double best = (p - path.front()).norm();
  for (std::size_t i = 1; i < path.size(); ++i) {
    best = std::min(best, testing::distance_to_segment(p, {path[i - 1], path[i]}));
  }
  return best;
}

// drives the follower in an empty world from `start` until it stops following or `seconds`
// pass; returns the largest distance from the path seen on the way
double drive(PathFollower& follower, testing::KinematicSim& sim, double seconds) {
  double worst = 0;
  for (int k = 0; k < static_cast<int>(seconds / 0.05); ++k) {
    const msg::Twist t = follower.command(sim.pose(), SimTime::from_ms(50) * k);
    if (follower.status() != PathStatus::following) break;
    sim.step(t, 0.05);
    worst = std::max(worst, distance_to_path(sim.pose().position(), follower.path()));
  }
  return worst;
}

TEST(PathFollower, IdleWithoutAPath) {
  PathFollower f;
  EXPECT_EQ(f.status(), PathStatus::idle);
  const msg::Twist t = f.command({}, SimTime{});
  EXPECT_EQ(t.linear.x(), 0.0);
  EXPECT_EQ(t.angular.z(), 0.0);
  f.set_path({}, SimTime{});
  EXPECT_EQ(f.status(), PathStatus::idle);
}

TEST(PathFollower, DrivesAStraightPathToItsEnd) {
  PathFollower f;
  f.set_path({{0.0, 0.0}, {4.0, 0.0}}, SimTime{});
  EXPECT_NEAR(f.remaining_length(), 4.0, 1e-12);
  const msg::Twist first = f.command({0, 0, 0}, SimTime{});
  EXPECT_NEAR(first.linear.x(), f.config().max_linear, 1e-9);
  EXPECT_NEAR(first.angular.z(), 0.0, 1e-9);

  testing::KinematicSim sim({}, {0, 0, 0}, {}, 0.35);
  const double off = drive(f, sim, 30.0);
  EXPECT_EQ(f.status(), PathStatus::reached);
  EXPECT_LT(off, 1e-6);
  EXPECT_LT((sim.pose().position() - Vec2(4.0, 0.0)).norm(), f.config().goal_tolerance);
  EXPECT_EQ(f.next_index(), 2u);
}

TEST(PathFollower, TurnsOnTheSpotTowardAPathBehind) {
  PathFollower f;
  f.set_path({{0.0, 0.0}, {-2.0, 1.0}}, SimTime{});
  const msg::Twist t = f.command({0, 0, 0}, SimTime{});  // target behind, to the left
  EXPECT_EQ(t.linear.x(), 0.0);
  EXPECT_GT(t.angular.z(), 0.5);
}

TEST(PathFollower, FollowsAnLShapedPathClosely) {
  PathFollower f;
  const std::vector<Vec2> path = {{0.0, 0.0}, {3.0, 0.0}, {3.0, 3.0}, {0.5, 3.0}};
  f.set_path(path, SimTime{});
  testing::KinematicSim sim({}, {0, 0, 0}, {}, 0.35);
  const double off = drive(f, sim, 60.0);
  EXPECT_EQ(f.status(), PathStatus::reached);
  EXPECT_LT(off, 0.25);  // corners are cut by about the lookahead's reach
  EXPECT_LT((sim.pose().position() - path.back()).norm(), f.config().goal_tolerance);
}

TEST(PathFollower, ReportsStuckWhenTheRobotMakesNoProgress) {
  PathFollower f;
  f.set_path({{0.0, 0.0}, {4.0, 0.0}}, SimTime{});
  const Pose2 wedged{0.0, 0.0, 0.0};
  for (int ms = 0; ms <= 5000; ms += 50) {
    f.command(wedged, SimTime::from_ms(ms));
    ASSERT_EQ(f.status(), PathStatus::following) << ms;
  }
  const msg::Twist t = f.command(wedged, SimTime::from_ms(5100));
  EXPECT_EQ(f.status(), PathStatus::stuck);
  EXPECT_EQ(t.linear.x(), 0.0);
}

TEST(PathFollower, ASinglePointIsDrivenTo) {
  PathFollower f;
  f.set_path({{1.5, -1.0}}, SimTime{});
  testing::KinematicSim sim({}, {0, 0, 0}, {}, 0.35);
  drive(f, sim, 30.0);
  EXPECT_EQ(f.status(), PathStatus::reached);
  EXPECT_LT((sim.pose().position() - Vec2(1.5, -1.0)).norm(), f.config().goal_tolerance);
}

TEST(PathFollower, ProgressIsMeasuredAlongThePath) {
  PathFollower f;
  f.set_path({{0.0, 0.0}, {2.0, 0.0}, {2.0, 2.0}}, SimTime{});
  f.command({1.0, 0.1, 0.0}, SimTime{});
  EXPECT_NEAR(f.remaining_length(), 3.0, 1e-9);
  EXPECT_EQ(f.next_index(), 1u);
  f.command({2.1, 0.5, M_PI / 2}, SimTime::from_ms(50));
  EXPECT_NEAR(f.remaining_length(), 1.5, 1e-9);
  EXPECT_EQ(f.next_index(), 2u);
  // progress never goes back
  f.command({1.0, 0.0, 0.0}, SimTime::from_ms(100));
  EXPECT_NEAR(f.remaining_length(), 1.5, 1e-9);
}

}  // namespace
}  // namespace rescuesim::autonomy
