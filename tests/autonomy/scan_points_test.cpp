#include "autonomy/scan_points.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace rescuesim::autonomy {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// four beams at -90, 0, 90 and 180 degrees
msg::LaserScan four_beams(std::vector<float> ranges) {
  msg::LaserScan s;
  s.angle_min = static_cast<float>(-M_PI / 2);
  s.angle_increment = static_cast<float>(M_PI / 2);
  s.angle_max = static_cast<float>(M_PI);
  s.range_min = 0.1f;
  s.range_max = 5.0f;
  s.ranges = std::move(ranges);
  return s;
}

TEST(ScanPoints, Rep117RangesArePlacedOrDropped) {
  // -inf: too close (placed at range_min); +inf, >= range_max: no return; NaN, below min: invalid
  const auto points = scan_points_in_base(four_beams({-kInf, 2.0f, kInf, std::nanf("")}), {});
  ASSERT_EQ(points.size(), 2u);
  EXPECT_TRUE(points[0].p_B.isApprox(Vec2(0.0, -0.1), 1e-6));
  EXPECT_TRUE(points[0].too_close);
  EXPECT_TRUE(points[1].p_B.isApprox(Vec2(2.0, 0.0), 1e-6));
  EXPECT_FALSE(points[1].too_close);
  EXPECT_NEAR(points[1].distance_B, 2.0, 1e-6);
  EXPECT_TRUE(scan_points_in_base(four_beams({5.0f, 0.05f, 7.0f, kInf}), {}).empty());
}

TEST(ScanPoints, MountingPoseMovesThePointsIntoTheBaseFrame) {
  // laser 0.2 m ahead of the base, facing left: its x axis is the base's y axis
  const auto points = scan_points_in_base(four_beams({kInf, 1.0f, kInf, kInf}), {0.2, 0.0, M_PI / 2});
  ASSERT_EQ(points.size(), 1u);
  EXPECT_TRUE(points[0].p_B.isApprox(Vec2(0.2, 1.0), 1e-6));
  EXPECT_NEAR(points[0].bearing_B, std::atan2(1.0, 0.2), 1e-6);
}

TEST(ScanPoints, FreeTravelOfADisc) {
  auto at = [](double x, double y) { return ScanPoint{Vec2(x, y), std::atan2(y, x), std::hypot(x, y), false}; };
  // straight ahead: x - r; off-axis: x - sqrt(r^2 - y^2); outside the swept band or behind: nothing
  EXPECT_NEAR(free_distance_ahead({at(2.0, 0.0)}, 0.5), 1.5, 1e-12);
  EXPECT_NEAR(free_distance_ahead({at(2.0, 0.3)}, 0.5), 1.6, 1e-12);
  EXPECT_TRUE(std::isinf(free_distance_ahead({at(2.0, 0.6), at(-1.0, 0.0)}, 0.5)));
  EXPECT_EQ(free_distance_ahead({at(0.3, 0.0)}, 0.5), 0.0);
  // with a margin: dearer ahead, but a return already beside the robot inside the margin is passed
  EXPECT_NEAR(free_distance_ahead({at(2.0, 0.0)}, 0.5, 0.1), 1.4, 1e-12);
  EXPECT_TRUE(std::isinf(free_distance_ahead({at(0.05, 0.55)}, 0.5, 0.1)));
  // along another heading: the point (0, 2) lies dead ahead when heading left
  EXPECT_NEAR(free_distance_along({at(0.0, 2.0)}, M_PI / 2, 0.5), 1.5, 1e-12);
}

ScanPoint at(int beam, double x, double y) {
  ScanPoint p;
  p.p_B = {x, y};
  p.distance_B = p.p_B.norm();
  p.beam = beam;
  return p;
}

TEST(ScanPoints, ThinReturnsStandingAloneAreFoundAndNothingElse) {
  std::vector<ScanPoint> points;
  points.push_back(at(9, 4.0, -0.5));  // background, 2 m behind the post
  for (int k = 0; k < 3; ++k) points.push_back(at(10 + k, 2.0, -0.02 + 0.02 * k));  // a post 4 cm wide; beam 13 returns nothing
  for (int k = 0; k <= 25; ++k) points.push_back(at(20 + k, 3.0, 0.5 + 0.04 * k));  // a wall 1 m long
  points.push_back(at(49, 1.1, 0.95));  // a thin thing just in front of a wall: not alone
  points.push_back(at(50, 1.0, 1.0));
  points.push_back(at(51, 1.0, 1.03));
  points.push_back(at(52, 1.12, 1.05));
  points.push_back(at(60, 2.0, 2.0));  // one beam alone: noise, not a post
  for (int k = 0; k < 6; ++k) points.push_back(at(70 + k, -2.0, 0.04 * k));  // alone, but 20 cm wide
  const auto posts = thin_returns(points, Vec2::Zero(), 0.09, 0.3);
  ASSERT_EQ(posts.size(), 1u);
  EXPECT_TRUE(posts[0].isApprox(Vec2(2.0, 0.0), 1e-12));
  // the same post with the background 0.2 m behind it: not standing alone
  points[0] = at(9, 2.2, -0.05);
  EXPECT_TRUE(thin_returns(points, Vec2::Zero(), 0.09, 0.3).empty());
  // and with nothing around it at all
  EXPECT_EQ(thin_returns({at(0, 1.0, 0.0), at(1, 1.0, 0.03)}, Vec2::Zero(), 0.09, 0.3).size(), 1u);
}

}  // namespace
}  // namespace rescuesim::autonomy
