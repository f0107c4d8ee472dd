// Scan-to-map matching on grids mapped from exact scans of known rooms (kinematic_sim.h's ray
// caster, walls 0.1 m thick): a scan taken from a pose offset from the prediction is put back
// where it was taken; in a corridor longer than the laser's reach the shift along it is
// reported ambiguous and left alone; the likelihood field is the Gaussian of the distance.

#include "autonomy/scan_matcher.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "autonomy/kinematic_sim.h"
#include "autonomy/scan_points.h"

namespace rescuesim::autonomy {
namespace {

using testing::KinematicSim;
using testing::Segment;

constexpr double kDeg = M_PI / 180;

// a fixed 30 m grid centred on the origin, mapped from exact 360-beam scans at `poses`
OccupancyMapper map_of(const std::vector<Segment>& walls, const std::vector<Pose2>& poses, double range_max) {
  OccupancyMapperConfig c;
  c.size = Vec2(30, 30);
  c.origin_O = Vec2(-15, -15);
  OccupancyMapper map(c);
  for (const Pose2& X : poses) {
    for (int k = 0; k < 3; ++k) {  // a few times over, so every wall cell is firmly occupied
      KinematicSim sim(walls, X, Pose2{}, 0.1, range_max);
      map.integrate(sim.scan(SimTime{}), X);
    }
  }
  return map;
}

// the returns of an exact scan from X_MB, in base_link (the laser at the base origin)
std::vector<Vec2> points_from(const std::vector<Segment>& walls, const Pose2& X_MB, double range_max) {
  KinematicSim sim(walls, X_MB, Pose2{}, 0.1, range_max);
  std::vector<Vec2> p_B;
  for (const ScanPoint& s : scan_points_in_base(sim.scan(SimTime{}), Pose2{})) p_B.push_back(s.p_B);
  return p_B;
}

// an L-shaped room: 6 m x 6 m less its upper-right 3 m x 3 m quarter
std::vector<Segment> l_room() {
  return {{{0, 0}, {6, 0}}, {{6, 0}, {6, 3}}, {{6, 3}, {3, 3}}, {{3, 3}, {3, 6}}, {{3, 6}, {0, 6}}, {{0, 6}, {0, 0}}};
}

TEST(LikelihoodField, IsTheGaussianOfTheDistanceToTheNearestOccupiedCell) {
  OccupancyMapperConfig c;
  c.size = Vec2(2, 2);
  OccupancyMapper map(c);
  map.set_state({20, 20}, CellState::occupied);
  LikelihoodField f;
  f.build(map, {0, 0}, {39, 39}, 0.06, 0.25);
  // one cell (0.05 m) away: exp(-0.05^2 / (2 * 0.06^2)) = exp(-0.3472) = 0.7066; a diagonal
  // (0.0707 m): exp(-0.6944) = 0.4994; 6 cells (0.3 m) is beyond the reach: 0
  EXPECT_NEAR(f.at({20, 20}), 1.0, 1e-6);
  EXPECT_NEAR(f.at({21, 20}), 0.7066, 1e-4);
  EXPECT_NEAR(f.at({20, 19}), 0.7066, 1e-4);
  EXPECT_NEAR(f.at({21, 21}), 0.4994, 1e-4);
  EXPECT_EQ(f.at({26, 20}), 0.0);
  EXPECT_EQ(f.at({-1, 20}), 0.0);  // outside the box
  // half-way between two cell centres: the mean of the two, and the slope between them; on
  // the row of centres the slope across is taken towards the next row up:
  // (0.5 (0.7066 - 1) + 0.5 (0.4994 - 0.7066)) / 0.05 = -5.006 per m
  Vec2 grad;
  const Vec2 mid = map.cell_to_world({20, 20}) + Vec2(0.025, 0);
  EXPECT_NEAR(f.interpolate(mid, &grad), 0.5 * (1 + 0.7066), 1e-4);
  EXPECT_NEAR(grad.x(), (0.7066 - 1) / 0.05, 1e-2);
  EXPECT_NEAR(grad.y(), -5.006, 1e-2);
}

TEST(ScanMatcher, RecoversAnOffsetPoseInAnLShapedRoom) {
  const auto walls = l_room();
  const OccupancyMapper map = map_of(walls, {{1.5, 1.5, 0}, {4.5, 1.5, 0}, {1.5, 4.5, 0}}, 10.0);
  // the truth is (0.1 m, -0.05 m, 3 deg) off the prediction
  const Pose2 truth{2.0, 2.0, 0.4};
  const Pose2 predicted{truth.x - 0.1, truth.y + 0.05, truth.yaw - 3 * kDeg};
  ScanMatcher matcher;
  const ScanMatch m = matcher.match(map, points_from(walls, truth, 10.0), predicted);
  EXPECT_EQ(m.verdict, MatchVerdict::good);
  EXPECT_LT((m.X_MB.position() - truth.position()).norm(), 0.05);  // one cell
  EXPECT_LT(std::abs(wrap_angle(m.X_MB.yaw - truth.yaw)), 0.5 * kDeg);
  EXPECT_GT(m.score, m.predicted_score);
  EXPECT_LT(m.spread_major, matcher.config().max_spread);
}

TEST(ScanMatcher, AtThePredictionItStaysThere) {
  const auto walls = l_room();
  const OccupancyMapper map = map_of(walls, {{1.5, 1.5, 0}, {4.5, 1.5, 0}, {1.5, 4.5, 0}}, 10.0);
  const Pose2 truth{1.2, 4.0, -2.0};
  ScanMatcher matcher;
  const ScanMatch m = matcher.match(map, points_from(walls, truth, 10.0), truth);
  EXPECT_EQ(m.verdict, MatchVerdict::good);
  EXPECT_LT((m.X_MB.position() - truth.position()).norm(), 0.03);
  EXPECT_LT(std::abs(wrap_angle(m.X_MB.yaw - truth.yaw)), 0.5 * kDeg);
}

TEST(ScanMatcher, ALongCorridorLeavesTheShiftAlongItUncorrected) {
  // 40 m of corridor 2 m wide, a laser reaching 8 m: its ends are never seen
  const std::vector<Segment> walls{{{-20, 0}, {20, 0}}, {{-20, 2}, {20, 2}}};
  const OccupancyMapper map = map_of(walls, {{-4, 1, 0}, {0, 1, 0}, {4, 1, 0}}, 8.0);
  const Pose2 truth{0.0, 1.0, 0.1};
  const Pose2 predicted{truth.x - 0.15, truth.y + 0.05, truth.yaw - 2 * kDeg};
  ScanMatcher matcher;
  const ScanMatch m = matcher.match(map, points_from(walls, truth, 8.0), predicted);
  EXPECT_EQ(m.verdict, MatchVerdict::ambiguous);
  EXPECT_GT(std::abs(m.major_axis_M.x()), 0.95);  // the loose direction is along the corridor
  EXPECT_GT(m.spread_major, matcher.config().max_spread);
  // across the corridor and the heading are corrected; along it the prediction stands
  EXPECT_NEAR(m.X_MB.y, truth.y, 0.05);
  EXPECT_LT(std::abs(wrap_angle(m.X_MB.yaw - truth.yaw)), 0.5 * kDeg);
  EXPECT_NEAR(m.X_MB.x, predicted.x, 0.02);
}

TEST(ScanMatcher, NothingToMatchAgainstKeepsThePrediction) {
  OccupancyMapperConfig c;
  c.size = Vec2(10, 10);
  c.origin_O = Vec2(-5, -5);
  const OccupancyMapper empty(c);
  const auto walls = l_room();
  const Pose2 predicted{2.0, 2.0, 0.0};
  ScanMatcher matcher;
  const ScanMatch m = matcher.match(empty, points_from(walls, predicted, 10.0), predicted);
  EXPECT_EQ(m.verdict, MatchVerdict::rejected);
  EXPECT_EQ(m.X_MB.x, predicted.x);
  EXPECT_EQ(m.X_MB.y, predicted.y);
  EXPECT_EQ(m.X_MB.yaw, predicted.yaw);
  // and too few points is no match either
  const OccupancyMapper map = map_of(walls, {{1.5, 1.5, 0}}, 10.0);
  const ScanMatch few = matcher.match(map, {Vec2(1, 0), Vec2(0, 1)}, predicted);
  EXPECT_EQ(few.verdict, MatchVerdict::rejected);
}

}  // namespace
}  // namespace rescuesim::autonomy
